!> The Fortran module's argument checks: every array against the batch size, sets of optional
!> arguments given whole, a normal required; each failure returns its status, changes nothing,
!> and leaves a message. Also the single-precision apply, reading a law's constants back and
!> the keep-on-wall capture mode.
!> Run by crates/capi/tests/examples.rs (also under valgrind); stops with a message on failure.
program checks
  use, intrinsic :: iso_c_binding, only: c_double, c_float, c_int8_t, c_int64_t
  use depo
  implicit none
  integer, parameter :: dp = c_double, sp = c_float
  type(depo_law_t) :: law, kept
  type(depo_law_params) :: params
  real(dp) :: sx(1), sy(1), sz(1)
  integer(c_int8_t) :: so(1)
  type(depo_tally) :: tally
  real(dp) :: vx(4), vy(4), vz(4), nx(4), ny(4), nz(4), wx(4), wy(4), wz(4), radius(4), vc(4)
  real(dp) :: short(3), e(4), r(4), vn(4), empty(0), mass(4), deposited(2)
  real(sp) :: vx32(4), vy32(4), vz32(4), short32(3)
  integer(c_int8_t) :: outcome(4), outcome32(4), captured(3)
  integer(c_int64_t) :: face(4), count(2)
  integer :: ierr, failures
  type(depo_air) :: air
  real(dp) :: u_star(2), layer(2), diameter(2), density(2), chance(2), v_d(2)

  failures = 0
  call depo_law_create(law, depo_law_params(12.5_dp, 12.5_dp, 0.065_dp, 0.065_dp, 1.0_dp, 0.5_dp, 0.074_dp, 0.3_dp))
  call depo_law_get_params(law, params)
  call check(params%k1 == 12.5_dp .and. params%kappa2 == 0.065_dp .and. params%q == 0.5_dp .and. params%mu == 0.3_dp, &
             'depo_law_get_params reads the constants back')

  ! Keep-on-wall capture: a slow oblique hit is captured with only its normal velocity zeroed.
  call depo_law_keeping_on_wall(law, DEPO_CAPTURE_KEEP_ON_WALL, kept, ierr)
  call check(ierr == DEPO_OK, 'depo_law_keeping_on_wall')
  sx = 0.2_dp
  sy = -0.1_dp
  sz = -0.03_dp
  call depo_apply(kept, sx, sy, sz, so, normal=[0.0_dp, 0.0_dp, 1.0_dp], ierr=ierr)
  call check(ierr == DEPO_OK .and. so(1) == DEPO_CAPTURED .and. sz(1) == 0.0_dp .and. sx(1) > 0.0_dp, &
             'a captured particle kept on the wall keeps its tangential velocity')
  call depo_law_destroy(kept)
  call depo_law_keeping_on_wall(law, 7, kept, ierr)
  call check(ierr == DEPO_ERR_INVALID .and. index(depo_last_error_message(), 'capture mode 7') > 0, &
             'an unknown capture mode is refused')

  ! Sizes: each array of the wrong size fails with DEPO_ERR_INVALID and changes nothing.
  call reset()
  call depo_apply(law, vx, short, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'vy', 'vy of the wrong size')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, nx=nx, ny=ny, nz=short, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'nz', 'nz of the wrong size')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], wx=wx, wy=short, wz=wz, radius=radius, &
                  ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'wy', 'wy of the wrong size')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], wx=wx, wy=wy, wz=wz, radius=short, &
                  ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'radius', 'radius of the wrong size')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], capture_velocity=short, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'capture_velocity', 'capture_velocity of the wrong size')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], capture_velocity=empty, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'capture_velocity', 'an empty capture_velocity')

  ! Partial sets fail as C fails them (DEPO_ERR_NULL), and no normal at all as a zero normal.
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, nx=nx, ny=ny, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_NULL, 'nx, ny and nz', 'nx, ny without nz')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], wx=wx, wy=wy, radius=radius, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_NULL, 'wx, wy, wz and radius', 'wx, wy, radius without wz')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], wx=wx, wy=wy, wz=wz, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_NULL, 'radius', 'spin without radius')
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'normal', 'no normal at all')
  ! libdepo's own failures still come through, with libdepo's message.
  call reset()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 2.0_dp], ierr=ierr)
  call unchanged(ierr, DEPO_ERR_INVALID, 'batch normal has length 2', 'a batch normal not of unit length')

  ! A full call works, in double and single precision alike.
  call reset()
  tally = depo_tally()
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp], wx=wx, wy=wy, wz=wz, radius=radius, &
                  tally=tally, ierr=ierr)
  call check(ierr == DEPO_OK .and. all(outcome == DEPO_REBOUND) .and. all(vz > 0.0_dp), 'a full f64 call rebounds')
  call check(tally%rebound == 4, 'the tally counts the rebounds')
  call reset()
  vx32 = real(vx, sp)
  vy32 = real(vy, sp)
  vz32 = real(vz, sp)
  outcome32 = -1
  call depo_apply(law, vx32, vy32, short32, outcome32, normal=[0.0_sp, 0.0_sp, 1.0_sp], ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID .and. all(outcome32 == -1), 'f32: vz of the wrong size')
  call depo_apply(law, vx32, vy32, vz32, outcome32, normal=[0.0_sp, 0.0_sp, 1.0_sp], ierr=ierr)
  call depo_apply(law, vx, vy, vz, outcome, normal=[0.0_dp, 0.0_dp, 1.0_dp])
  call check(ierr == DEPO_OK .and. all(outcome32 == outcome), 'f32 and f64 outcomes agree')
  call check(all(abs(real(vz32, dp) - vz) <= 1.0e-4_dp), 'f32 and f64 velocities agree')

  ! Coefficients: every output of the size of vn.
  vn = [-1.0_dp, -0.5_dp, -0.05_dp, 2.0_dp]
  e = 9.0_dp
  call depo_coefficients(law, vn, e=e, r=short, ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID .and. all(e == 9.0_dp), 'coefficients: r of the wrong size')
  call depo_coefficients(law, vn, e=empty, ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID, 'coefficients: an empty e')
  captured = 7
  call depo_coefficients(law, vn, e=e, captured=captured, ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID .and. all(e == 9.0_dp) .and. all(captured == 7), &
             'coefficients: captured of the wrong size')
  call depo_coefficients(law, vn, e=e, r=r, ierr=ierr)
  call check(ierr == DEPO_OK .and. abs(e(1) - 0.731990683_dp) < 1.0e-8_dp, 'coefficients of the right sizes')

  ! Deposition map: mass like outcome, deposited_mass like count, both or neither.
  outcome = [DEPO_CAPTURED, DEPO_REBOUND, DEPO_CAPTURED, DEPO_CAPTURED]
  face = [0, 1, 1, 1]
  mass = 1.0_dp
  count = 0
  deposited = 0.0_dp
  call depo_accumulate_deposits(outcome, face, count, mass=short, deposited_mass=deposited, ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID .and. all(count == 0), 'deposits: mass of the wrong size')
  call depo_accumulate_deposits(outcome, face, count, mass=mass, deposited_mass=short, ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID .and. all(count == 0) .and. all(short == 0.0_dp), &
             'deposits: deposited_mass of the wrong size')
  call depo_accumulate_deposits(outcome, face, count, mass=mass, ierr=ierr)
  call check(ierr == DEPO_ERR_NULL .and. all(count == 0), 'deposits: mass without deposited_mass')
  call depo_accumulate_deposits(outcome, face, count, mass=mass, deposited_mass=deposited, ierr=ierr)
  call check(ierr == DEPO_OK .and. all(count == [1, 2]) .and. all(deposited == [1.0_dp, 2.0_dp]), 'deposits counted')

  ! Wall function: the chance is 1 - exp(-v_d dt / layer) of the deposition velocity; a bad
  ! layer is refused and writes nothing.
  u_star = [0.3_dp, 0.01_dp]
  layer = [1.5e-3_dp, 4.5e-2_dp]
  diameter = [5.0e-6_dp, 1.0e-6_dp]
  density = 1000.0_dp
  call depo_deposition_velocity(DEPO_CORRELATION_WOOD, DEPO_SURFACE_WALL, air, 0.0_dp, u_star, diameter, density, &
                                v_d, ierr=ierr)
  call check(ierr == DEPO_OK .and. all(v_d > 0.0_dp), 'deposition velocities')
  call depo_wall_function_probability(DEPO_CORRELATION_WOOD, DEPO_SURFACE_WALL, air, 0.0_dp, 1.0e-3_dp, u_star, &
                                      layer, diameter, density, chance, ierr=ierr)
  call check(ierr == DEPO_OK .and. all(abs(chance - (1.0_dp - exp(-v_d * 1.0e-3_dp / layer))) < 1.0e-15_dp), &
             'wall-function chances')
  chance = 7.0_dp
  layer(2) = -1.0_dp
  call depo_wall_function_probability(DEPO_CORRELATION_LAI_NAZAROFF, DEPO_SURFACE_FLOOR, air, 9.81_dp, 0.1_dp, &
                                      u_star, layer, diameter, density, chance, ierr=ierr)
  call check(ierr == DEPO_ERR_INVALID .and. all(chance == 7.0_dp) .and. index(depo_last_error_message(), 'layer[1]') > 0, &
             'a negative layer')

  ! Threads: a negative count is refused, not passed on as a huge size; so is an absurd one.
  call depo_set_num_threads(-1, ierr)
  call check(ierr == DEPO_ERR_INVALID, 'a negative thread count')
  call depo_set_num_threads(100000, ierr)
  call check(ierr == DEPO_ERR_INVALID .and. index(depo_last_error_message(), 'DEPO_MAX_THREADS') > 0, &
             'an absurd thread count, with libdepo''s message')
  call depo_set_num_threads(1, ierr)
  call check(ierr == DEPO_OK, 'one thread')

  call depo_law_destroy(law)
  if (failures > 0) error stop 'fortran checks failed'
  print '(a)', 'fortran checks passed'

contains

  subroutine reset()
    vx = [0.1_dp, -0.2_dp, 0.0_dp, 0.3_dp]
    vy = 0.05_dp
    vz = [-1.0_dp, -2.0_dp, -0.5_dp, -3.0_dp]
    nx = 0.0_dp
    ny = 0.0_dp
    nz = 1.0_dp
    wx = 0.0_dp
    wy = 100.0_dp
    wz = 0.0_dp
    radius = 2.0e-5_dp
    vc = 0.074_dp
    short = 0.0_dp
    outcome = -1
  end subroutine reset

  !> A call that must fail with status, a message containing word, and change nothing.
  subroutine unchanged(got, status, word, what)
    integer, intent(in) :: got
    integer(kind(DEPO_OK)), intent(in) :: status
    character(len=*), intent(in) :: word, what
    call check(got == status, what//': status')
    call check(index(depo_last_error_message(), word) > 0, what//': message "'//depo_last_error_message()//'"')
    call check(all(outcome == -1) .and. all(vz == [-1.0_dp, -2.0_dp, -0.5_dp, -3.0_dp]) .and. all(wy == 100.0_dp), &
               what//': nothing changed')
  end subroutine unchanged

  subroutine check(ok, what)
    logical, intent(in) :: ok
    character(len=*), intent(in) :: what
    if (.not. ok) then
      print '(a, a)', 'FAILED: ', what
      failures = failures + 1
    end if
  end subroutine check

end program checks
