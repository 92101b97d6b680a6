! Check case: every boundary face is a smooth wall for the air. (Code_Saturne 6.0 stops
! unless this Fortran routine is given when no GUI setup file is used.)

subroutine cs_f_user_boundary_conditions &
 ( nvar   , nscal  ,                                              &
   icodcl , itrifb , itypfb , izfppp ,                            &
   dt     ,                                                       &
   rcodcl )

use paramx
use mesh

implicit none

integer          nvar   , nscal
integer          icodcl(nfabor,nvar)
integer          itrifb(nfabor), itypfb(nfabor)
integer          izfppp(nfabor)
double precision dt(ncelet)
double precision rcodcl(nfabor,nvar,3)

integer          ifac

do ifac = 1, nfabor
  itypfb(ifac) = iparoi
enddo

return
end subroutine cs_f_user_boundary_conditions
