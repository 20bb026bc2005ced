#include "limsurf/apps/hodge.h"
