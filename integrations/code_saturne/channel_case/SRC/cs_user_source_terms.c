/* Channel: the driving pressure gradient, -dp/dx = rho u*^2 / H, as a uniform momentum
   source along x (the periodic flow has no mean pressure drop of its own). */

#include "cs_defs.h"
#include "cs_domain.h"
#include "cs_field.h"
#include "cs_field_pointer.h"
#include "cs_mesh.h"
#include "cs_mesh_quantities.h"
#include "cs_prototypes.h"

#include "channel.h"

BEGIN_C_DECLS

void
cs_user_source_terms(cs_domain_t  *domain,
                     int           f_id,
                     cs_real_t    *st_exp,
                     cs_real_t    *st_imp)
{
  CS_UNUSED(domain);
  CS_UNUSED(st_imp);
  if (f_id != CS_F_(vel)->id)
    return;
  const cs_real_t *vol = cs_glob_mesh_quantities->cell_vol;
  cs_real_3_t *st = (cs_real_3_t *)st_exp;
  for (cs_lnum_t c = 0; c < cs_glob_mesh->n_cells; c++)
    st[c][0] += CHANNEL_GRADIENT * vol[c];
}

END_C_DECLS
