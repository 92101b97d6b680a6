/* Check case: one-way particle tracking, no turbulent dispersion, no gravity; Code_Saturne's
   boundary statistics accumulated over the whole run (steady statistics from the first step),
   so that depo_check_statistics.c can compare them with depo's contacts. */

#include "cs_defs.h"
#include "cs_lagr.h"
#include "cs_lagr_stat.h"
#include "cs_prototypes.h"

BEGIN_C_DECLS

void
cs_user_lagr_model(void)
{
  cs_glob_lagr_time_scheme->iilagr = CS_LAGR_ONEWAY_COUPLING;
  cs_glob_lagr_time_scheme->isuila = 0;
  cs_glob_lagr_time_scheme->isttio = 1;
  cs_glob_lagr_stat_options->nstist = 1;
  cs_glob_lagr_stat_options->idstnt = 1;
  cs_glob_lagr_time_scheme->t_order = 1;
  cs_glob_lagr_model->physical_model = 0;
  cs_glob_lagr_time_scheme->idistu = 0;
  cs_glob_lagr_time_scheme->idiffl = 0;
  cs_glob_lagr_model->deposition = 0;

  cs_glob_lagr_boundary_interactions->has_part_impact_nbr = 1;
  cs_lagr_stat_activate(CS_LAGR_STAT_E_CUMULATIVE_WEIGHT);
  cs_lagr_stat_activate(CS_LAGR_STAT_MASS_FLUX);
  cs_lagr_stat_activate_time_moment(CS_LAGR_STAT_MASS_FLUX, CS_LAGR_MOMENT_MEAN);
  cs_lagr_stat_activate(CS_LAGR_STAT_IMPACT_ANGLE);
  cs_lagr_stat_activate(CS_LAGR_STAT_IMPACT_VELOCITY);
}

END_C_DECLS
