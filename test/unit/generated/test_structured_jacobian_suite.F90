!> The structured Jacobian of the head/neck model (a_ij with the element
!! stiffness K and damping C: d(xddot)/dx = -a^-1 K, d(xddot)/dxdot =
!! -a^-1 C) against forward differences of the full evaluation at five
!! random states near the NBDL deck's posture: the damping block, which
!! carries the stiff modes (discs' viscosity, joint dampers), within 1 %
!! (measured 0.07-0.45 %) and the stiffness block within 30 % (measured
!! 21-23 %: the structured form leaves out the geometric stiffness of the
!! loaded elements, the dependence of a_ij, gravity and the velocity terms
!! on x -- what a W-method tolerates).
module test_structured_jacobian
    use funit
    use hn_kinds, only: wp, zero, one, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_dynamics, only: model_ode_t, model_ode_init, state_size, coordinates_to_state
    use hn_iteration_matrix, only: fd_jacobian
    use hn_random, only: rng_t
    implicit none

contains

    !@test
    subroutine test_structured_against_differences()
        type(case_t) :: cs
        type(model_ode_t) :: sys
        type(rng_t) :: rng
        real(wp), allocatable :: y(:), f(:), jfd(:, :), m(:, :), k(:, :), c(:, :), j21(:, :), j22(:, :), x(:), xd(:)
        real(wp) :: e21, e22, eall
        integer :: stat, nf, is, j
        character(len=msglen) :: msg
        character(len=200) :: d
        call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
#line 33 "/work/main/test/unit/test_structured_jacobian.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_structured_jacobian.pf', &
 & 33) )
  if (anyExceptions()) return
#line 34 "/work/main/test/unit/test_structured_jacobian.pf"
        call model_ode_init(sys, cs%model)
        nf = sys%ws%nfree
        allocate (y(state_size(sys)), f(state_size(sys)), jfd(state_size(sys), state_size(sys)))
        allocate (m(nf, nf), k(nf, nf), c(nf, nf), x(size(cs%x0)), xd(size(cs%x0)))
        call rng%seed(2024)
        do is = 1, 5
            do j = 1, size(x)
                x(j) = cs%x0(j) + rng%uniform(-0.05_wp, 0.05_wp)
                xd(j) = rng%uniform(-2.0_wp, 2.0_wp)
            end do
            call coordinates_to_state(sys%ws, x, xd, y)
            call sys%rhs(0.02_wp*is, y, f, stat, msg)
#line 46 "/work/main/test/unit/test_structured_jacobian.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_structured_jacobian.pf', &
 & 46) )
  if (anyExceptions()) return
#line 47 "/work/main/test/unit/test_structured_jacobian.pf"
            call fd_jacobian(sys, 0.02_wp*is, y, f, jfd, stat, msg)
            call sys%second_order_tangent(0.02_wp*is, y, m, k, c, stat, msg)
#line 49 "/work/main/test/unit/test_structured_jacobian.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_structured_jacobian.pf', &
 & 49) )
  if (anyExceptions()) return
#line 50 "/work/main/test/unit/test_structured_jacobian.pf"
            j21 = -solve(m, k)
            j22 = -solve(m, c)
            e21 = norm2(j21 - jfd(nf + 1:2*nf, 1:nf))/norm2(jfd(nf + 1:2*nf, 1:nf))
            e22 = norm2(j22 - jfd(nf + 1:2*nf, nf + 1:2*nf))/norm2(jfd(nf + 1:2*nf, nf + 1:2*nf))
            eall = sqrt(sum((j21 - jfd(nf + 1:2*nf, 1:nf))**2) + sum((j22 - jfd(nf + 1:2*nf, nf + 1:2*nf))**2)) &
                   /norm2(jfd(nf + 1:2*nf, 1:2*nf))
            write (d, '(a,i0,a,3es10.2)') 'state ', is, ': rel. differences K block, C block, all ', e21, e22, eall
            print '(a)', trim(d)
#line 58 "/work/main/test/unit/test_structured_jacobian.pf"
  call assertTrue(e22 < 0.01_wp, 'damping block within 1 %: '//trim(d), &
 & location=SourceLocation( &
 & 'test_structured_jacobian.pf', &
 & 58) )
  if (anyExceptions()) return
#line 59 "/work/main/test/unit/test_structured_jacobian.pf"
#line 59 "/work/main/test/unit/test_structured_jacobian.pf"
  call assertTrue(e21 < 0.3_wp, 'stiffness block within 30 %: '//trim(d), &
 & location=SourceLocation( &
 & 'test_structured_jacobian.pf', &
 & 59) )
  if (anyExceptions()) return
#line 60 "/work/main/test/unit/test_structured_jacobian.pf"
#line 60 "/work/main/test/unit/test_structured_jacobian.pf"
  call assertTrue(eall < 0.3_wp, 'whole Jacobian within 30 %: '//trim(d), &
 & location=SourceLocation( &
 & 'test_structured_jacobian.pf', &
 & 60) )
  if (anyExceptions()) return
#line 61 "/work/main/test/unit/test_structured_jacobian.pf"
        end do
    end subroutine test_structured_against_differences

    !> m^-1 b by Gaussian elimination (test-local, no pivoting needed: m SPD).
    function solve(m, b) result(x)
        real(wp), intent(in) :: m(:, :), b(:, :)
        real(wp) :: x(size(b, 1), size(b, 2)), a(size(m, 1), size(m, 2)), r
        integer :: i, j, n
        a = m; x = b; n = size(m, 1)
        do i = 1, n
            do j = i + 1, n
                r = a(j, i)/a(i, i)
                a(j, i:n) = a(j, i:n) - r*a(i, i:n)
                x(j, :) = x(j, :) - r*x(i, :)
            end do
        end do
        do i = n, 1, -1
            x(i, :) = (x(i, :) - matmul(a(i, i + 1:n), x(i + 1:n, :)))/a(i, i)
        end do
    end function solve

end module test_structured_jacobian

module Wraptest_structured_jacobian
   use FUnit
   use test_structured_jacobian
   implicit none
   private

contains


end module Wraptest_structured_jacobian

function test_structured_jacobian_suite() result(suite)
   use FUnit
   use test_structured_jacobian
   use Wraptest_structured_jacobian
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_structured_jacobian_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_structured_against_differences', &
      test_structured_against_differences))
   call suite%addTest(t)


end function test_structured_jacobian_suite

