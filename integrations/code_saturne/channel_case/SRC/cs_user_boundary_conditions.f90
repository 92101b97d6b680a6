! Channel: every boundary face left after the periodic joining is a smooth wall (with
! Code_Saturne's wall functions).

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
