/* Channel: periodic along the flow (x, box_mesh.py's groups 4 and 5) and across the span
   (y, group 3), leaving the walls z = 0 and z = 2H. */

#include "cs_defs.h"
#include "cs_join_perio.h"
#include "cs_prototypes.h"

#include "channel.h"

BEGIN_C_DECLS

void
cs_user_periodicity(void)
{
  const double along[3] = {CHANNEL_LX, 0.0, 0.0};
  const double across[3] = {0.0, CHANNEL_LY, 0.0};
  cs_join_perio_add_translation("4 or 5", 0.1, 25.0, 0, 0, along);
  cs_join_perio_add_translation("3", 0.1, 25.0, 0, 0, across);
}

END_C_DECLS
