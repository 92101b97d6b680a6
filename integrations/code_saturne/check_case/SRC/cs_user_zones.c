/* Boundary zones of the check case. Code_Saturne 6.0 names the groups of a Gmsh mesh by
   their physical tags: 1 is the floor, 2 the ceiling, 3 to 5 the four side walls
   (box_mesh.py). */

#include "cs_defs.h"
#include "cs_boundary_zone.h"
#include "cs_prototypes.h"

BEGIN_C_DECLS

void
cs_user_zones(void)
{
  cs_boundary_zone_define("floor", "1", 0);
  cs_boundary_zone_define("ceiling", "2", 0);
  cs_boundary_zone_define("walls", "3 or 4 or 5", 0);
}

END_C_DECLS
