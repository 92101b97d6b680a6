/* Channel: the flow stage starts from a plug flow of 6 m/s (about the bulk velocity at
   Re_tau 480), which develops sooner than from rest. A restart keeps its fields. */

#include "cs_defs.h"
#include "cs_domain.h"
#include "cs_field.h"
#include "cs_field_pointer.h"
#include "cs_mesh.h"
#include "cs_prototypes.h"
#include "cs_time_step.h"

BEGIN_C_DECLS

void
cs_user_initialization(cs_domain_t *domain)
{
  CS_UNUSED(domain);
  if (cs_glob_time_step->nt_prev > 0)
    return;
  cs_real_3_t *u = (cs_real_3_t *)CS_F_(vel)->val;
  for (cs_lnum_t c = 0; c < cs_glob_mesh->n_cells; c++) {
    u[c][0] = 6.0;
    u[c][1] = 0.0;
    u[c][2] = 0.0;
  }
}

END_C_DECLS
