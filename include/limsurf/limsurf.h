// Umbrella header: everything public in limsurf.
#pragma once

#include "limsurf/core/error.h"
#include "limsurf/core/types.h"
#include "limsurf/core/version.h"
#include "limsurf/io/atomic_file.h"
#include "limsurf/io/mesh_io.h"
#include "limsurf/io/obj.h"
#include "limsurf/io/off.h"
#include "limsurf/io/ply.h"
#include "limsurf/io/vertex_field.h"
#include "limsurf/io/vtk.h"
#include "limsurf/mesh/control_mesh.h"
#include "limsurf/mesh/polygon_soup.h"
#include "limsurf/mesh/sharpness.h"
#include "limsurf/mesh/statistics.h"
#include "limsurf/mesh/topology.h"
#include "limsurf/mesh/validate.h"
