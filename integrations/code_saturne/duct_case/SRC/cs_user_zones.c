/* Boundary zones of the duct (box_mesh.py's groups by number): air enters at x = 0 and
   leaves at x = 2 m; the floor, the ceiling and the two sides are walls. */

#include "cs_defs.h"
#include "cs_boundary_zone.h"
#include "cs_prototypes.h"

BEGIN_C_DECLS

void
cs_user_zones(void)
{
  cs_boundary_zone_define("floor", "1", 0);
  cs_boundary_zone_define("ceiling", "2", 0);
  cs_boundary_zone_define("sides", "3", 0);
  cs_boundary_zone_define("inlet", "4", 0);
  cs_boundary_zone_define("outlet", "5", 0);
}

END_C_DECLS
