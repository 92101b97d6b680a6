! Duct: air enters at x = 0 at 1 m/s (turbulence from the pipe laws for the 0.2 m hydraulic
! diameter), leaves freely at x = 2 m; every other face is a smooth wall.

subroutine cs_f_user_boundary_conditions &
 ( nvar   , nscal  ,                                              &
   icodcl , itrifb , itypfb , izfppp ,                            &
   dt     ,                                                       &
   rcodcl )

use paramx
use numvar
use optcal
use cstphy
use mesh
use field
use cs_c_bindings

implicit none

integer          nvar   , nscal
integer          icodcl(nfabor,nvar)
integer          itrifb(nfabor), itypfb(nfabor)
integer          izfppp(nfabor)
double precision dt(ncelet)
double precision rcodcl(nfabor,nvar,3)

integer          ifac, ilelt, nlelt
double precision uref2, rhomoy
integer, allocatable, dimension(:) :: lstelt
double precision, dimension(:), pointer :: bfpro_rom

allocate(lstelt(nfabor))
call field_get_val_s(ibrom, bfpro_rom)

do ifac = 1, nfabor
  itypfb(ifac) = iparoi
enddo

call getfbr('4', nlelt, lstelt)
do ilelt = 1, nlelt
  ifac = lstelt(ilelt)
  itypfb(ifac) = ientre
  rcodcl(ifac,iu,1) = 1.d0
  rcodcl(ifac,iv,1) = 0.d0
  rcodcl(ifac,iw,1) = 0.d0
  uref2 = 1.d0
  rhomoy = bfpro_rom(ifac)
  call turbulence_bc_inlet_hyd_diam(ifac, uref2, 0.2d0, rhomoy, viscl0, rcodcl)
enddo

call getfbr('5', nlelt, lstelt)
do ilelt = 1, nlelt
  ifac = lstelt(ilelt)
  itypfb(ifac) = isolib
enddo

deallocate(lstelt)

return
end subroutine cs_f_user_boundary_conditions
