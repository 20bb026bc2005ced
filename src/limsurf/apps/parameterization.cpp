#include "limsurf/apps/parameterization.h"
