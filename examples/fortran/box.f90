!> depo from Fortran: particles of 35 to 140 um in a box under gravity, each with its own
!> capture velocity; each step's wall hits go to depo as one batch on the solver's own arrays;
!> captured particles are removed.
!> From the repository root, after the one release build (README), linked statically:
!>   gfortran crates/capi/fortran/depo.f90 examples/fortran/box.f90 target/release/libdepo.a -lpthread -ldl -lm -o box
!> or after `crates/capi/install.sh $HOME/.local`, with PKG_CONFIG_PATH=$HOME/.local/lib/pkgconfig:
!>   gfortran $HOME/.local/share/depo/fortran/depo.f90 examples/fortran/box.f90 $(pkg-config --libs depo) -o box
program box
  use, intrinsic :: iso_c_binding, only: c_double, c_int8_t, c_int64_t
  use depo
  implicit none
  integer, parameter :: dp = c_double
  integer :: injected, airborne, deposited, hits, i, k, a, step, wall, kept, ierr
  real(dp), allocatable :: x(:, :), v(:, :), hv(:, :), hn(:, :), diameter(:), vc(:), hvc(:)
  integer, allocatable :: idx(:)
  integer(c_int64_t), allocatable :: hface(:)
  integer(c_int64_t) :: deposited_on(6)
  integer(c_int8_t), allocatable :: outcome(:)
  logical, allocatable :: gone(:)
  real(dp) :: xa, sign, e(2), r(2)
  real(dp), parameter :: dt = 1.0e-3_dp, gravity = -9.81_dp
  type(depo_law_t) :: law, bad
  type(depo_tally) :: tally
  character(len=32) :: arg
  integer(8) :: seed

  injected = 20000
  if (command_argument_count() > 0) then
    call get_command_argument(1, arg)
    read (arg, *) injected
  end if
  print '(a, a)', 'depo ', depo_version_string()

  call depo_law_create(bad, depo_law_params(12.5_dp, 12.5_dp, 0.065_dp, 0.065_dp, 1.0_dp, 0.5_dp, 0.074_dp, -1.0_dp), ierr)
  if (ierr /= DEPO_ERR_INVALID) error stop 'bad parameters accepted'
  print '(a, a)', 'rejected: ', depo_last_error_message()

  call depo_law_create(law, depo_law_params(12.5_dp, 12.5_dp, 0.065_dp, 0.065_dp, 1.0_dp, 0.5_dp, 0.074_dp, 0.3_dp))
  call depo_coefficients(law, [-1.0_dp, -0.05_dp], e=e, r=r)
  print '(a, f8.5, a, f8.5)', 'e(1 m/s) = ', e(1), '  e(0.05 m/s) = ', e(2)

  allocate (x(injected, 3), v(injected, 3), hv(injected, 3), hn(injected, 3), idx(injected), outcome(injected))
  allocate (gone(injected), diameter(injected), vc(injected), hvc(injected), hface(injected))
  deposited_on = 0
  seed = 12345
  do i = 1, injected
    do a = 1, 3
      x(i, a) = 0.05_dp + 0.9_dp*uniform(seed)
      v(i, a) = (uniform(seed) - 0.5_dp)*4.0_dp*uniform(seed)
    end do
    diameter(i) = 35.0e-6_dp + 105.0e-6_dp*uniform(seed)
  end do
  ! The law's vc holds at 70 um; vc ~ d**(-1.51) across sizes (paper Fig. 8).
  call depo_capture_velocities(law, 70.0e-6_dp, 1.51_dp, diameter, vc)

  airborne = injected
  deposited = 0
  do step = 1, 2000
    hits = 0
    do i = 1, airborne
      v(i, 3) = v(i, 3) + gravity*dt
      wall = 0
      sign = 0
      do a = 1, 3
        xa = x(i, a) + v(i, a)*dt
        if (xa < 0.0_dp .or. xa > 1.0_dp) then
          if (wall == 0) then
            wall = a
            sign = merge(1.0_dp, -1.0_dp, xa < 0.0_dp)
          end if
          xa = merge(-xa, 2.0_dp - xa, xa < 0.0_dp)
        end if
        x(i, a) = xa
      end do
      if (wall > 0) then
        hits = hits + 1
        idx(hits) = i
        hv(hits, :) = v(i, :)
        hn(hits, :) = 0.0_dp
        hn(hits, wall) = sign
        hvc(hits) = vc(i)
        hface(hits) = 2*(wall - 1) + merge(0, 1, sign > 0.0_dp)
      end if
    end do
    ! The batch: columns of the solver's hit arrays, passed by address.
    call depo_apply(law, hv(1:hits, 1), hv(1:hits, 2), hv(1:hits, 3), outcome(1:hits), &
                    nx=hn(1:hits, 1), ny=hn(1:hits, 2), nz=hn(1:hits, 3), &
                    capture_velocity=hvc(1:hits), tally=tally)
    call depo_accumulate_deposits(outcome(1:hits), hface(1:hits), deposited_on)
    gone(1:airborne) = .false.
    do k = 1, hits
      if (outcome(k) == DEPO_CAPTURED) then
        gone(idx(k)) = .true.
        deposited = deposited + 1
      else
        v(idx(k), :) = hv(k, :)
      end if
    end do
    kept = 0
    do i = 1, airborne
      if (gone(i)) cycle
      kept = kept + 1
      x(kept, :) = x(i, :)
      v(kept, :) = v(i, :)
      vc(kept) = vc(i)
    end do
    airborne = kept
  end do

  print '(a, i0, a, i0, a, i0)', 'injected ', injected, ' airborne ', airborne, ' deposited ', deposited
  print '(a, i0, a, i0, a, i0, a, i0)', 'tally rebound ', tally%rebound, ' captured ', tally%captured, &
    ' skipped ', tally%skipped, ' invalid ', tally%invalid
  print '(a, 6(1x, i0))', 'deposited per wall (x0 x1 y0 y1 z0 z1):', deposited_on
  call depo_law_destroy(law)
  call depo_law_destroy(bad)
  if (airborne + deposited /= injected .or. tally%captured /= int(deposited, c_int64_t)) error stop 'particles lost'
  if (sum(deposited_on) /= int(deposited, c_int64_t)) error stop 'deposition map does not add up'

contains

  function uniform(state) result(u)
    integer(8), intent(inout) :: state
    real(dp) :: u
    state = modulo(state*16807_8, 2147483647_8)
    u = real(state, dp)/2147483647.0_dp
  end function uniform

end program box
