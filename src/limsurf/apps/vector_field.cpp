#include "limsurf/apps/vector_field.h"
