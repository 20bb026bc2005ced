#include "limsurf/apps/geodesics.h"
