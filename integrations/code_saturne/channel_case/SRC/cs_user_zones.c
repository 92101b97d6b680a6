/* Channel: the two walls (box_mesh.py's floor and ceiling); the other faces are joined by
   periodicity. */

#include "cs_defs.h"
#include "cs_boundary_zone.h"
#include "cs_prototypes.h"

BEGIN_C_DECLS

void
cs_user_zones(void)
{
  cs_boundary_zone_define("floor", "1", 0);
  cs_boundary_zone_define("ceiling", "2", 0);
}

END_C_DECLS
