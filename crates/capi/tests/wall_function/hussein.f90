! Hussein et al.'s (2012) wall function through the Fortran module: the same particles as
! hussein.c, printed the same way, and a refused particle with its status.
program hussein
  use, intrinsic :: iso_c_binding, only: c_double, c_int32_t
  use depo
  implicit none
  integer, parameter :: dp = c_double
  type(depo_air) :: air
  real(dp), parameter :: gravity = 9.80665_dp, dt = 1.0e-3_dp
  real(dp) :: u_star(4), diameter(4), density(4), layer(4), v(4), p(4), u1(1), d1(1), rho1(1), out(1)
  integer(c_int32_t) :: s
  integer :: i, ierr
  u_star = [0.3_dp, 0.01_dp, 0.5_dp, 0.2_dp]
  diameter = [5.0e-6_dp, 3.0e-6_dp, 40.0e-6_dp, 0.1e-6_dp]
  density = [1000.0_dp, 1500.0_dp, 2500.0_dp, 1000.0_dp]
  layer = [1.5e-3_dp, 0.045_dp, 2.0e-3_dp, 4.0e-3_dp]
  do s = DEPO_SURFACE_FLOOR, DEPO_SURFACE_WALL
    call depo_deposition_velocity(DEPO_CORRELATION_HUSSEIN, s, air, gravity, u_star, diameter, density, v)
    call depo_wall_function_probability(DEPO_CORRELATION_HUSSEIN, s, air, gravity, dt, u_star, layer, diameter, &
                                        density, p)
    do i = 1, 4
      write (*, '(a, i0, 7(1x, es25.17e3))') 'hussein ', s, u_star(i), diameter(i), density(i), layer(i), dt, &
        v(i), p(i)
    end do
  end do
  u1 = 10.0_dp
  d1 = 1.0e-3_dp
  rho1 = 1000.0_dp
  out = -1.0_dp
  call depo_deposition_velocity(DEPO_CORRELATION_HUSSEIN, DEPO_SURFACE_WALL, air, gravity, u1, d1, rho1, out, ierr)
  write (*, '(a, i0, 1x, f4.1, 1x, a)') 'refused ', ierr, out(1), depo_last_error_message()
end program hussein
