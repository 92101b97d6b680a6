/* Check case: every boundary zone takes its law from DATA/depo_zones. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_prototypes.h"

#include "depo_code_saturne.h"

BEGIN_C_DECLS

void
cs_user_lagr_boundary_conditions(const int  bc_type[])
{
  CS_UNUSED(bc_type);
  depo_cs_setup(cs_lagr_get_boundary_conditions());
}

END_C_DECLS
