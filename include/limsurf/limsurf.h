// Umbrella header: everything public in limsurf.
#pragma once

#include "limsurf/core/error.h"
#include "limsurf/core/types.h"
#include "limsurf/core/version.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/statistics.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/mesh/validate.h"
