!> depo: the Brach & Dunn (1998) wall law for Lagrangian particles, from Fortran.
!>
!> A thin layer over libdepo's C ABI (depo.h): interoperable types, bind(C) interfaces, and
!> friendly wrappers with an optional ierr argument (absent: a failure stops the program with
!> depo's message). Arrays pass by address, never copied: the solver's own arrays are updated
!> in place. Free a law with depo_law_destroy; nothing relies on final procedures.
!>
!> Every array is checked against the batch size before libdepo sees it, and optional arguments
!> that come in sets (nx, ny, nz; wx, wy, wz with radius; mass with deposited_mass) are given
!> whole or not at all: otherwise the call fails (DEPO_ERR_INVALID for a size, DEPO_ERR_NULL
!> for a partial set, as C), changes nothing, and depo_last_error_message() says why.
!> depo_apply takes double (c_double) or single (c_float) precision arrays.
module depo
  use, intrinsic :: iso_c_binding
  implicit none
  private

  public :: depo_law_t, depo_law_params, depo_tally
  public :: DEPO_OK, DEPO_ERR_NULL, DEPO_ERR_INVALID, DEPO_ERR_PANIC
  public :: DEPO_REBOUND, DEPO_CAPTURED, DEPO_SKIPPED, DEPO_INVALID
  public :: depo_law_create, depo_law_from_preset, depo_law_destroy, depo_law_get_params
  public :: depo_law_keeping_on_wall, DEPO_CAPTURE_DEPOSIT, DEPO_CAPTURE_KEEP_ON_WALL
  public :: depo_apply, depo_coefficients, depo_capture_velocities, depo_accumulate_deposits
  public :: depo_set_num_threads
  public :: depo_air, depo_deposition_velocity, depo_wall_function_probability
  public :: DEPO_CORRELATION_WOOD, DEPO_CORRELATION_PAPAVERGOS_HEDLEY, DEPO_CORRELATION_LAI_NAZAROFF
  public :: DEPO_CORRELATION_HUSSEIN
  public :: DEPO_SURFACE_FLOOR, DEPO_SURFACE_CEILING, DEPO_SURFACE_WALL
  public :: depo_last_error_message, depo_version_string

  !> Status codes (int32_t).
  integer(c_int32_t), parameter :: DEPO_OK = 0, DEPO_ERR_NULL = 1, DEPO_ERR_INVALID = 2, DEPO_ERR_PANIC = 3
  !> Outcome per particle (uint8_t in C, integer(c_int8_t) here).
  integer(c_int8_t), parameter :: DEPO_REBOUND = 0_c_int8_t, DEPO_CAPTURED = 1_c_int8_t, &
                                  DEPO_SKIPPED = 2_c_int8_t, DEPO_INVALID = 3_c_int8_t
  !> Capture modes (depo_law_keeping_on_wall).
  integer, parameter :: DEPO_CAPTURE_DEPOSIT = 0, DEPO_CAPTURE_KEEP_ON_WALL = 1

  !> Deposition correlations and surface orientations of the wall function (depo.h says what
  !> each is; DEPO_CORRELATION_HUSSEIN's velocities are cached per thread by their inputs).
  integer(c_int32_t), parameter :: DEPO_CORRELATION_WOOD = 0, DEPO_CORRELATION_PAPAVERGOS_HEDLEY = 1, &
                                   DEPO_CORRELATION_LAI_NAZAROFF = 2, DEPO_CORRELATION_HUSSEIN = 3
  integer(c_int32_t), parameter :: DEPO_SURFACE_FLOOR = 0, DEPO_SURFACE_CEILING = 1, DEPO_SURFACE_WALL = 2

  !> The carrier gas (DepoAir): K, Pa, kg/m^3, Pa s; dry air at 20 C by default.
  type, bind(C) :: depo_air
    real(c_double) :: temperature = 293.15_c_double, pressure = 101325.0_c_double
    real(c_double) :: density = 1.204_c_double, viscosity = 1.81e-5_c_double
  end type depo_air

  !> The constants of the law, SI units (DepoLawParams).
  type, bind(C) :: depo_law_params
    real(c_double) :: k1, k2, kappa1, kappa2, p, q, vc, mu
  end type depo_law_params

  !> Outcome counts and energy lost per unit mass (J/kg); depo adds to it (DepoTally).
  type, bind(C) :: depo_tally
    integer(c_int64_t) :: rebound = 0, captured = 0, skipped = 0, invalid = 0
    real(c_double) :: energy_material = 0, energy_adhesion = 0, energy_friction = 0, energy_deposition = 0
  end type depo_tally

  !> DepoImpactsF64: the batch as pointers into the caller's arrays.
  type, bind(C) :: depo_impacts_f64
    integer(c_size_t) :: n = 0
    type(c_ptr) :: vx = c_null_ptr, vy = c_null_ptr, vz = c_null_ptr
    type(c_ptr) :: wx = c_null_ptr, wy = c_null_ptr, wz = c_null_ptr
    type(c_ptr) :: radius = c_null_ptr
    type(c_ptr) :: nx = c_null_ptr, ny = c_null_ptr, nz = c_null_ptr
    real(c_double) :: normal(3) = [0.0_c_double, 0.0_c_double, 1.0_c_double]
    type(c_ptr) :: outcome = c_null_ptr
  end type depo_impacts_f64

  !> DepoImpactsF32: depo_impacts_f64 in single precision.
  type, bind(C) :: depo_impacts_f32
    integer(c_size_t) :: n = 0
    type(c_ptr) :: vx = c_null_ptr, vy = c_null_ptr, vz = c_null_ptr
    type(c_ptr) :: wx = c_null_ptr, wy = c_null_ptr, wz = c_null_ptr
    type(c_ptr) :: radius = c_null_ptr
    type(c_ptr) :: nx = c_null_ptr, ny = c_null_ptr, nz = c_null_ptr
    real(c_float) :: normal(3) = [0.0_c_float, 0.0_c_float, 1.0_c_float]
    type(c_ptr) :: outcome = c_null_ptr
  end type depo_impacts_f32

  !> An opaque wall law.
  type :: depo_law_t
    private
    type(c_ptr) :: ptr = c_null_ptr
  end type depo_law_t

  !> Applies the law in place to a batch of double or single precision arrays.
  interface depo_apply
    module procedure depo_apply_f64, depo_apply_f32
  end interface depo_apply

  !> The message of the last failure found on the Fortran side (sizes, partial sets), cleared
  !> by a failure of libdepo's own; one per thread under OpenMP.
  character(len=256), save :: wrapper_error = ''
  !$omp threadprivate(wrapper_error)

  interface
    function c_depo_law_new(params, out) bind(C, name="depo_law_new") result(status)
      import :: depo_law_params, c_ptr, c_int32_t
      type(depo_law_params), intent(in) :: params
      type(c_ptr), intent(out) :: out
      integer(c_int32_t) :: status
    end function c_depo_law_new

    function c_depo_law_preset(id, out) bind(C, name="depo_law_preset") result(status)
      import :: c_char, c_ptr, c_int32_t
      character(kind=c_char), intent(in) :: id(*)
      type(c_ptr), intent(out) :: out
      integer(c_int32_t) :: status
    end function c_depo_law_preset

    function c_depo_law_with_capture_mode(law, mode, out) bind(C, name="depo_law_with_capture_mode") &
        result(status)
      import :: c_ptr, c_int32_t
      type(c_ptr), value :: law
      integer(c_int32_t), value :: mode
      type(c_ptr), intent(out) :: out
      integer(c_int32_t) :: status
    end function c_depo_law_with_capture_mode

    function c_depo_law_params(law, params) bind(C, name="depo_law_params") result(status)
      import :: depo_law_params, c_ptr, c_int32_t
      type(c_ptr), value :: law
      type(depo_law_params), intent(out) :: params
      integer(c_int32_t) :: status
    end function c_depo_law_params

    subroutine c_depo_law_free(law) bind(C, name="depo_law_free")
      import :: c_ptr
      type(c_ptr), value :: law
    end subroutine c_depo_law_free

    function c_depo_apply_f64(law, batch, tally) bind(C, name="depo_apply_f64") result(status)
      import :: c_ptr, depo_impacts_f64, c_int32_t
      type(c_ptr), value :: law
      type(depo_impacts_f64), intent(inout) :: batch
      type(c_ptr), value :: tally
      integer(c_int32_t) :: status
    end function c_depo_apply_f64

    function c_depo_apply_sized_f64(law, batch, vc, tally) bind(C, name="depo_apply_sized_f64") result(status)
      import :: c_ptr, depo_impacts_f64, c_int32_t
      type(c_ptr), value :: law
      type(depo_impacts_f64), intent(inout) :: batch
      type(c_ptr), value :: vc, tally
      integer(c_int32_t) :: status
    end function c_depo_apply_sized_f64

    function c_depo_apply_f32(law, batch, tally) bind(C, name="depo_apply_f32") result(status)
      import :: c_ptr, depo_impacts_f32, c_int32_t
      type(c_ptr), value :: law
      type(depo_impacts_f32), intent(inout) :: batch
      type(c_ptr), value :: tally
      integer(c_int32_t) :: status
    end function c_depo_apply_f32

    function c_depo_apply_sized_f32(law, batch, vc, tally) bind(C, name="depo_apply_sized_f32") result(status)
      import :: c_ptr, depo_impacts_f32, c_int32_t
      type(c_ptr), value :: law
      type(depo_impacts_f32), intent(inout) :: batch
      type(c_ptr), value :: vc, tally
      integer(c_int32_t) :: status
    end function c_depo_apply_sized_f32

    function c_depo_capture_velocities(law, reference_diameter, exponent, n, diameter, vc) &
      bind(C, name="depo_capture_velocities") result(status)
      import :: c_ptr, c_double, c_size_t, c_int32_t
      type(c_ptr), value :: law, diameter, vc
      real(c_double), value :: reference_diameter, exponent
      integer(c_size_t), value :: n
      integer(c_int32_t) :: status
    end function c_depo_capture_velocities

    function c_depo_accumulate_deposits(n, outcome, face, mass, nfaces, count, deposited_mass) &
      bind(C, name="depo_accumulate_deposits") result(status)
      import :: c_ptr, c_size_t, c_int32_t
      integer(c_size_t), value :: n, nfaces
      type(c_ptr), value :: outcome, face, mass, count, deposited_mass
      integer(c_int32_t) :: status
    end function c_depo_accumulate_deposits

    function c_depo_deposition_velocity(correlation, orientation, air, gravity, n, u, d, rho, v) &
      bind(C, name="depo_deposition_velocity") result(status)
      import :: c_ptr, c_double, c_size_t, c_int32_t, depo_air
      integer(c_int32_t), value :: correlation, orientation
      type(depo_air), intent(in) :: air
      real(c_double), value :: gravity
      integer(c_size_t), value :: n
      type(c_ptr), value :: u, d, rho, v
      integer(c_int32_t) :: status
    end function c_depo_deposition_velocity

    function c_depo_wall_function_probability(correlation, orientation, air, gravity, dt, n, u, layer, d, rho, p) &
      bind(C, name="depo_wall_function_probability") result(status)
      import :: c_ptr, c_double, c_size_t, c_int32_t, depo_air
      integer(c_int32_t), value :: correlation, orientation
      type(depo_air), intent(in) :: air
      real(c_double), value :: gravity, dt
      integer(c_size_t), value :: n
      type(c_ptr), value :: u, layer, d, rho, p
      integer(c_int32_t) :: status
    end function c_depo_wall_function_probability

    function c_depo_coefficients(law, n, vn, e, r, rho, captured) bind(C, name="depo_coefficients") result(status)
      import :: c_ptr, c_size_t, c_int32_t
      type(c_ptr), value :: law, vn, e, r, rho, captured
      integer(c_size_t), value :: n
      integer(c_int32_t) :: status
    end function c_depo_coefficients

    function c_depo_set_num_threads(threads) bind(C, name="depo_set_num_threads") result(status)
      import :: c_size_t, c_int32_t
      integer(c_size_t), value :: threads
      integer(c_int32_t) :: status
    end function c_depo_set_num_threads

    function c_depo_last_error() bind(C, name="depo_last_error") result(message)
      import :: c_ptr
      type(c_ptr) :: message
    end function c_depo_last_error

    function c_depo_version() bind(C, name="depo_version") result(version)
      import :: c_ptr
      type(c_ptr) :: version
    end function c_depo_version

    function c_strlen(s) bind(C, name="strlen") result(length)
      import :: c_ptr, c_size_t
      type(c_ptr), value :: s
      integer(c_size_t) :: length
    end function c_strlen
  end interface

contains

  !> A C string as a Fortran string.
  function from_c_string(p) result(s)
    type(c_ptr), intent(in) :: p
    character(len=:), allocatable :: s
    character(kind=c_char), pointer :: chars(:)
    integer :: i, length
    length = int(c_strlen(p))
    call c_f_pointer(p, chars, [length])
    allocate (character(len=length) :: s)
    do i = 1, length
      s(i:i) = chars(i)
    end do
  end function from_c_string

  !> The message of the last failure on this thread, found by this module or by libdepo.
  function depo_last_error_message() result(message)
    character(len=:), allocatable :: message
    if (len_trim(wrapper_error) > 0) then
      message = trim(wrapper_error)
    else
      message = from_c_string(c_depo_last_error())
    end if
  end function depo_last_error_message

  !> The library version, "MAJOR.MINOR.PATCH".
  function depo_version_string() result(version)
    character(len=:), allocatable :: version
    version = from_c_string(c_depo_version())
  end function depo_version_string

  !> Passes status to ierr, or stops with depo's message when ierr is absent.
  subroutine handle(status, ierr)
    integer(c_int32_t), intent(in) :: status
    integer, intent(out), optional :: ierr
    if (status /= DEPO_OK) wrapper_error = ''
    if (present(ierr)) then
      ierr = int(status)
    else if (status /= DEPO_OK) then
      error stop "depo: "//depo_last_error_message()
    end if
  end subroutine handle

  !> Reports a failure found on the Fortran side: status (DEPO_ERR_INVALID unless given) to
  !> ierr with the message kept for depo_last_error_message, or stops with the message when
  !> ierr is absent.
  subroutine fail(message, ierr, status)
    character(len=*), intent(in) :: message
    integer, intent(out), optional :: ierr
    integer(c_int32_t), intent(in), optional :: status
    wrapper_error = message
    if (present(ierr)) then
      ierr = DEPO_ERR_INVALID
      if (present(status)) ierr = int(status)
    else
      error stop "depo: "//message
    end if
  end subroutine fail

  !> The size of an optional array, -1 when absent.
  pure integer function size_or_absent_f64(x) result(length)
    real(c_double), intent(in), optional :: x(:)
    length = -1
    if (present(x)) length = size(x)
  end function size_or_absent_f64

  pure integer function size_or_absent_f32(x) result(length)
    real(c_float), intent(in), optional :: x(:)
    length = -1
    if (present(x)) length = size(x)
  end function size_or_absent_f32

  !> Checks depo_apply's arguments, given their sizes (-1: absent): every array of size n, sets
  !> of optional arguments given whole, a normal given one way or the other. Returns DEPO_OK,
  !> or the status for fail() with the message in problem.
  subroutine check_apply(n, sizes, has_normal, status, problem)
    integer, intent(in) :: n
    !> vy, vz, outcome, nx, ny, nz, wx, wy, wz, radius, capture_velocity
    integer, intent(in) :: sizes(11)
    logical, intent(in) :: has_normal
    integer(c_int32_t), intent(out) :: status
    character(len=:), allocatable, intent(out) :: problem
    character(len=*), parameter :: names(11) = [character(len=16) :: 'vy', 'vz', 'outcome', 'nx', 'ny', 'nz', &
                                                'wx', 'wy', 'wz', 'radius', 'capture_velocity']
    character(len=24) :: sizes_text
    integer :: k
    status = DEPO_OK
    problem = ''
    do k = 1, 11
      if (sizes(k) >= 0 .and. sizes(k) /= n) then
        write (sizes_text, '(i0, a, i0)') sizes(k), ' but vx has ', n
        status = DEPO_ERR_INVALID
        problem = 'depo_apply: '//trim(names(k))//' has size '//trim(sizes_text)
        return
      end if
    end do
    if (any(sizes(4:6) >= 0) .and. .not. all(sizes(4:6) >= 0)) then
      status = DEPO_ERR_NULL
      problem = 'depo_apply: give nx, ny and nz together, or none of them'
    else if (any(sizes(7:10) >= 0) .and. .not. all(sizes(7:10) >= 0)) then
      status = DEPO_ERR_NULL
      problem = 'depo_apply: give wx, wy, wz and radius together, or none of them'
    else if (.not. has_normal .and. sizes(4) < 0) then
      status = DEPO_ERR_INVALID
      problem = 'depo_apply: give the wall normal, as normal or as nx, ny and nz'
    end if
  end subroutine check_apply

  !> Makes a law from its constants.
  subroutine depo_law_create(law, params, ierr)
    type(depo_law_t), intent(out) :: law
    type(depo_law_params), intent(in) :: params
    integer, intent(out), optional :: ierr
    call handle(c_depo_law_new(params, law%ptr), ierr)
  end subroutine depo_law_create

  !> Makes the law of a preset of the paper's Table 1, e.g. "li1997-sio2".
  subroutine depo_law_from_preset(law, id, ierr)
    type(depo_law_t), intent(out) :: law
    character(len=*), intent(in) :: id
    integer, intent(out), optional :: ierr
    call handle(c_depo_law_preset(trim(id)//c_null_char, law%ptr), ierr)
  end subroutine depo_law_from_preset

  !> A copy of `law` that treats captured particles by `mode`: DEPO_CAPTURE_DEPOSIT (velocity and
  !> spin zero, every law's default) or DEPO_CAPTURE_KEEP_ON_WALL (only the normal velocity
  !> zeroed; the particle stays on the wall and may migrate along it). Free both laws.
  subroutine depo_law_keeping_on_wall(law, mode, kept, ierr)
    type(depo_law_t), intent(in) :: law
    integer, intent(in) :: mode
    type(depo_law_t), intent(out) :: kept
    integer, intent(out), optional :: ierr
    call handle(c_depo_law_with_capture_mode(law%ptr, int(mode, c_int32_t), kept%ptr), ierr)
  end subroutine depo_law_keeping_on_wall

  !> Reads the constants of a law back (depo_law_params in C; the name depo_law_params is the
  !> type's here).
  subroutine depo_law_get_params(law, params, ierr)
    type(depo_law_t), intent(in) :: law
    type(depo_law_params), intent(out) :: params
    integer, intent(out), optional :: ierr
    call handle(c_depo_law_params(law%ptr, params), ierr)
  end subroutine depo_law_get_params

  !> Frees a law; a law never made is fine.
  subroutine depo_law_destroy(law)
    type(depo_law_t), intent(inout) :: law
    call c_depo_law_free(law%ptr)
    law%ptr = c_null_ptr
  end subroutine depo_law_destroy

  !> Threads for large batches (0: one per core; 1: only the calling thread, for OpenMP and MPI
  !> hosts; at most 1024). Batches below 65536 particles always run on the calling thread.
  subroutine depo_set_num_threads(threads, ierr)
    integer, intent(in) :: threads
    integer, intent(out), optional :: ierr
    if (threads < 0) then
      call fail("depo_set_num_threads: threads is negative", ierr)
      return
    end if
    call handle(c_depo_set_num_threads(int(threads, c_size_t)), ierr)
  end subroutine depo_set_num_threads

  !> Applies the law in place to the particles (vx, vy, vz) hitting a wall, with one batch
  !> normal or per-particle normals (nx, ny, nz) (one of the two is required), optional spin
  !> (wx, wy, wz with radius) and optional per-particle capture velocities (polydisperse
  !> batches, see depo_capture_velocities). outcome receives one DEPO_* code per particle;
  !> tally, when present, is added to. Every array has the size of vx. (Specific of depo_apply
  !> for c_double arrays.)
  subroutine depo_apply_f64(law, vx, vy, vz, outcome, normal, nx, ny, nz, wx, wy, wz, radius, capture_velocity, tally, &
                            ierr)
    type(depo_law_t), intent(in) :: law
    real(c_double), intent(inout), target, contiguous :: vx(:), vy(:), vz(:)
    integer(c_int8_t), intent(inout), target, contiguous :: outcome(:)
    real(c_double), intent(in), optional :: normal(3)
    real(c_double), intent(in), target, contiguous, optional :: nx(:), ny(:), nz(:), radius(:)
    real(c_double), intent(inout), target, contiguous, optional :: wx(:), wy(:), wz(:)
    real(c_double), intent(in), target, contiguous, optional :: capture_velocity(:)
    type(depo_tally), intent(inout), target, optional :: tally
    integer, intent(out), optional :: ierr
    type(depo_impacts_f64) :: batch
    type(c_ptr) :: tally_ptr, vc_ptr
    integer(c_int32_t) :: status
    character(len=:), allocatable :: problem
    integer :: n

    n = size(vx)
    call check_apply(n, [size(vy), size(vz), size(outcome), size_or_absent_f64(nx), size_or_absent_f64(ny), &
                         size_or_absent_f64(nz), size_or_absent_f64(wx), size_or_absent_f64(wy), size_or_absent_f64(wz), &
                         size_or_absent_f64(radius), size_or_absent_f64(capture_velocity)], present(normal), status, problem)
    if (status /= DEPO_OK) then
      call fail(problem, ierr, status)
      return
    end if
    batch%n = int(n, c_size_t)
    if (n > 0) then
      batch%vx = c_loc(vx)
      batch%vy = c_loc(vy)
      batch%vz = c_loc(vz)
      batch%outcome = c_loc(outcome)
      if (present(nx)) then
        batch%nx = c_loc(nx)
        batch%ny = c_loc(ny)
        batch%nz = c_loc(nz)
      end if
      if (present(wx)) then
        batch%wx = c_loc(wx)
        batch%wy = c_loc(wy)
        batch%wz = c_loc(wz)
        batch%radius = c_loc(radius)
      end if
    end if
    if (present(normal)) batch%normal = normal
    tally_ptr = c_null_ptr
    if (present(tally)) tally_ptr = c_loc(tally)
    if (present(capture_velocity)) then
      vc_ptr = c_null_ptr
      if (n > 0) vc_ptr = c_loc(capture_velocity)
      call handle(c_depo_apply_sized_f64(law%ptr, batch, vc_ptr, tally_ptr), ierr)
    else
      call handle(c_depo_apply_f64(law%ptr, batch, tally_ptr), ierr)
    end if
  end subroutine depo_apply_f64

  !> Applies the law in place to the particles (vx, vy, vz) hitting a wall, with one batch
  !> normal or per-particle normals (nx, ny, nz) (one of the two is required), optional spin
  !> (wx, wy, wz with radius) and optional per-particle capture velocities (polydisperse
  !> batches, see depo_capture_velocities). outcome receives one DEPO_* code per particle;
  !> tally, when present, is added to. Every array has the size of vx. (Specific of depo_apply
  !> for c_float arrays.)
  subroutine depo_apply_f32(law, vx, vy, vz, outcome, normal, nx, ny, nz, wx, wy, wz, radius, capture_velocity, tally, &
                            ierr)
    type(depo_law_t), intent(in) :: law
    real(c_float), intent(inout), target, contiguous :: vx(:), vy(:), vz(:)
    integer(c_int8_t), intent(inout), target, contiguous :: outcome(:)
    real(c_float), intent(in), optional :: normal(3)
    real(c_float), intent(in), target, contiguous, optional :: nx(:), ny(:), nz(:), radius(:)
    real(c_float), intent(inout), target, contiguous, optional :: wx(:), wy(:), wz(:)
    real(c_float), intent(in), target, contiguous, optional :: capture_velocity(:)
    type(depo_tally), intent(inout), target, optional :: tally
    integer, intent(out), optional :: ierr
    type(depo_impacts_f32) :: batch
    type(c_ptr) :: tally_ptr, vc_ptr
    integer(c_int32_t) :: status
    character(len=:), allocatable :: problem
    integer :: n

    n = size(vx)
    call check_apply(n, [size(vy), size(vz), size(outcome), size_or_absent_f32(nx), size_or_absent_f32(ny), &
                         size_or_absent_f32(nz), size_or_absent_f32(wx), size_or_absent_f32(wy), size_or_absent_f32(wz), &
                         size_or_absent_f32(radius), size_or_absent_f32(capture_velocity)], present(normal), status, problem)
    if (status /= DEPO_OK) then
      call fail(problem, ierr, status)
      return
    end if
    batch%n = int(n, c_size_t)
    if (n > 0) then
      batch%vx = c_loc(vx)
      batch%vy = c_loc(vy)
      batch%vz = c_loc(vz)
      batch%outcome = c_loc(outcome)
      if (present(nx)) then
        batch%nx = c_loc(nx)
        batch%ny = c_loc(ny)
        batch%nz = c_loc(nz)
      end if
      if (present(wx)) then
        batch%wx = c_loc(wx)
        batch%wy = c_loc(wy)
        batch%wz = c_loc(wz)
        batch%radius = c_loc(radius)
      end if
    end if
    if (present(normal)) batch%normal = normal
    tally_ptr = c_null_ptr
    if (present(tally)) tally_ptr = c_loc(tally)
    if (present(capture_velocity)) then
      vc_ptr = c_null_ptr
      if (n > 0) vc_ptr = c_loc(capture_velocity)
      call handle(c_depo_apply_sized_f32(law%ptr, batch, vc_ptr, tally_ptr), ierr)
    else
      call handle(c_depo_apply_f32(law%ptr, batch, tally_ptr), ierr)
    end if
  end subroutine depo_apply_f32

  !> Capture velocities (m/s) from diameters (m), paper Fig. 8:
  !> vc = vc_law (diameter / reference_diameter)**(-exponent); 1.51 in the paper, 5/6 for JKR.
  subroutine depo_capture_velocities(law, reference_diameter, exponent, diameter, capture_velocity, ierr)
    type(depo_law_t), intent(in) :: law
    real(c_double), intent(in) :: reference_diameter, exponent
    real(c_double), intent(in), target, contiguous :: diameter(:)
    real(c_double), intent(out), target, contiguous :: capture_velocity(:)
    integer, intent(out), optional :: ierr
    type(c_ptr) :: pd, pv
    if (size(capture_velocity) /= size(diameter)) then
      call fail("depo_capture_velocities: capture_velocity must have the size of diameter", ierr)
      return
    end if
    pd = c_null_ptr
    pv = c_null_ptr
    if (size(diameter) > 0) then
      pd = c_loc(diameter)
      pv = c_loc(capture_velocity)
    end if
    call handle(c_depo_capture_velocities(law%ptr, reference_diameter, exponent, int(size(diameter), c_size_t), pd, pv), &
                ierr)
  end subroutine depo_capture_velocities

  !> The coefficients e, R, rho and capture (1 or 0) at normal velocities vn (m/s).
  subroutine depo_coefficients(law, vn, e, r, rho, captured, ierr)
    type(depo_law_t), intent(in) :: law
    real(c_double), intent(in), target, contiguous :: vn(:)
    real(c_double), intent(out), target, contiguous, optional :: e(:), r(:), rho(:)
    integer(c_int8_t), intent(out), target, contiguous, optional :: captured(:)
    integer, intent(out), optional :: ierr
    type(c_ptr) :: pv, pe, pr, prho, pc
    integer :: n, sizes(3)
    pv = c_null_ptr; pe = c_null_ptr; pr = c_null_ptr; prho = c_null_ptr; pc = c_null_ptr
    n = size(vn)
    sizes = [size_or_absent_f64(e), size_or_absent_f64(r), size_or_absent_f64(rho)]
    if (any(sizes >= 0 .and. sizes /= n)) then
      call fail("depo_coefficients: e, r and rho must have the size of vn", ierr)
      return
    end if
    if (present(captured)) then
      if (size(captured) /= n) then
        call fail("depo_coefficients: captured must have the size of vn", ierr)
        return
      end if
    end if
    if (size(vn) > 0) then
      pv = c_loc(vn)
      if (present(e)) pe = c_loc(e)
      if (present(r)) pr = c_loc(r)
      if (present(rho)) prho = c_loc(rho)
      if (present(captured)) pc = c_loc(captured)
    end if
    call handle(c_depo_coefficients(law%ptr, int(size(vn), c_size_t), pv, pe, pr, prho, pc), ierr)
  end subroutine depo_coefficients

  !> Adds the particles a depo_apply call captured to a deposition map: count(face(i) + 1) += 1
  !> (face ids are 0-based, as the host's C arrays are) and, with mass and deposited_mass,
  !> deposited_mass(face(i) + 1) += mass(i) (kg). A face id outside 0..size(count)-1 of a
  !> captured particle is DEPO_ERR_INVALID and changes nothing.
  subroutine depo_accumulate_deposits(outcome, face, count, mass, deposited_mass, ierr)
    integer(c_int8_t), intent(in), target, contiguous :: outcome(:)
    integer(c_int64_t), intent(in), target, contiguous :: face(:)
    integer(c_int64_t), intent(inout), target, contiguous :: count(:)
    real(c_double), intent(in), target, contiguous, optional :: mass(:)
    real(c_double), intent(inout), target, contiguous, optional :: deposited_mass(:)
    integer, intent(out), optional :: ierr
    type(c_ptr) :: po, pf, pc, pm, pd
    po = c_null_ptr; pf = c_null_ptr; pc = c_null_ptr; pm = c_null_ptr; pd = c_null_ptr
    if (size(face) /= size(outcome)) then
      call fail("depo_accumulate_deposits: face must have the size of outcome", ierr)
      return
    end if
    if (present(mass) .neqv. present(deposited_mass)) then
      call fail("depo_accumulate_deposits: give mass and deposited_mass together, or neither", ierr, DEPO_ERR_NULL)
      return
    end if
    if (present(mass)) then
      if (size(mass) /= size(outcome) .or. size(deposited_mass) /= size(count)) then
        call fail("depo_accumulate_deposits: mass must have the size of outcome, deposited_mass that of count", ierr)
        return
      end if
    end if
    if (size(outcome) > 0) then
      po = c_loc(outcome)
      pf = c_loc(face)
    end if
    if (size(count) > 0) pc = c_loc(count)
    if (present(mass) .and. present(deposited_mass)) then
      if (size(mass) > 0) pm = c_loc(mass)
      if (size(deposited_mass) > 0) pd = c_loc(deposited_mass)
    end if
    call handle(c_depo_accumulate_deposits(int(size(outcome), c_size_t), po, pf, pm, int(size(count), c_size_t), pc, pd), ierr)
  end subroutine depo_accumulate_deposits

  !> The deposition velocity (m/s) a correlation gives onto a surface of an orientation, per
  !> particle: friction velocity u (m/s) of its wall cell, diameter d (m), density rho (kg/m^3);
  !> gravity (m/s^2) acts towards floors. See depo_deposition_velocity in depo.h.
  subroutine depo_deposition_velocity(correlation, orientation, air, gravity, u, d, rho, v, ierr)
    integer(c_int32_t), intent(in) :: correlation, orientation
    type(depo_air), intent(in) :: air
    real(c_double), intent(in) :: gravity
    real(c_double), intent(in), target, contiguous :: u(:), d(:), rho(:)
    real(c_double), intent(out), target, contiguous :: v(:)
    integer, intent(out), optional :: ierr
    type(c_ptr) :: pu, pd, pr, pv
    pu = c_null_ptr; pd = c_null_ptr; pr = c_null_ptr; pv = c_null_ptr
    if (size(d) /= size(u) .or. size(rho) /= size(u) .or. size(v) /= size(u)) then
      call fail("depo_deposition_velocity: d, rho and v must have the size of u", ierr)
      return
    end if
    if (size(u) > 0) then
      pu = c_loc(u); pd = c_loc(d); pr = c_loc(rho); pv = c_loc(v)
    end if
    call handle(c_depo_deposition_velocity(correlation, orientation, air, gravity, int(size(u), c_size_t), &
                                           pu, pd, pr, pv), ierr)
  end subroutine depo_deposition_velocity

  !> The chance p that a particle in a wall cell reaches the wall within a step dt (s):
  !> 1 - exp(-v_d dt / layer), layer (m) the wall cell's extent normal to the wall. See
  !> depo_wall_function_probability in depo.h for how a solver uses it.
  subroutine depo_wall_function_probability(correlation, orientation, air, gravity, dt, u, layer, d, rho, p, ierr)
    integer(c_int32_t), intent(in) :: correlation, orientation
    type(depo_air), intent(in) :: air
    real(c_double), intent(in) :: gravity, dt
    real(c_double), intent(in), target, contiguous :: u(:), layer(:), d(:), rho(:)
    real(c_double), intent(out), target, contiguous :: p(:)
    integer, intent(out), optional :: ierr
    type(c_ptr) :: pu, pl, pd, pr, pp
    pu = c_null_ptr; pl = c_null_ptr; pd = c_null_ptr; pr = c_null_ptr; pp = c_null_ptr
    if (size(layer) /= size(u) .or. size(d) /= size(u) .or. size(rho) /= size(u) .or. size(p) /= size(u)) then
      call fail("depo_wall_function_probability: layer, d, rho and p must have the size of u", ierr)
      return
    end if
    if (size(u) > 0) then
      pu = c_loc(u); pl = c_loc(layer); pd = c_loc(d); pr = c_loc(rho); pp = c_loc(p)
    end if
    call handle(c_depo_wall_function_probability(correlation, orientation, air, gravity, dt, int(size(u), c_size_t), &
                                                 pu, pl, pd, pr, pp), ierr)
  end subroutine depo_wall_function_probability

end module depo
