!> The Rosenbrock-W method ROS34PW2: convergence order 3 at fixed steps on
!! stiff problems with independent solutions -- a linear system with a
!! closed form (first-order form, dense finite-difference Jacobian), the
!! same kind of system in second-order form (structured tangent solve),
!! Van der Pol with mu = 1000 against a DOPRI5 reference at rtol 1e-12
!! (order 2 there: stiff order reduction) --
!! and its error control and dense output.
module test_stiff_integrators
    use funit
    use hn_kinds, only: wp, zero, one, two, msglen
    use hn_integrators, only: integrator_t, new_integrator
    use hn_ode, only: ode_system_t
    use hn_status, only: stat_ok
    implicit none

    real(wp), parameter :: loose = 1.0e6_wp   !! tolerance that accepts every step: fixed steps

    ! Stiff test problems with known solutions: a Prothero-Robinson-type
    ! linear system in first-order form, the same kind in second-order form
    ! with its exact mass, stiffness and damping (the structured path), and
    ! Van der Pol's oscillator with mu = 1000.

    !> y' = A (y - phi(t)) + phi'(t), phi = (sin t, cos t), A with eigenvalues
    !! -1 and -lambda (coupled): y = phi exactly from y(0) = phi(0), and a
    !! perturbation decays on both time scales.
    type, extends(ode_system_t) :: linear_stiff_t
        real(wp) :: lambda = 1.0e4_wp
    contains
        procedure :: rhs => linear_rhs
    end type linear_stiff_t

    !> x'' + c x' + k x = phi'' + c phi' + k phi, phi = sin t (overdamped,
    !! eigenvalues about -c and -k/c): x = sin t from x(0) = 0, x'(0) = 1;
    !! second order with the exact tangent M = 1, K = k, C = c.
    type, extends(ode_system_t) :: second_order_stiff_t
        real(wp) :: c = 1.0e4_wp, k = 1.0e2_wp
    contains
        procedure :: rhs => second_rhs
        procedure :: second_order_tangent => second_tangent
    end type second_order_stiff_t

    !> Van der Pol: y1' = y2, y2' = mu (1 - y1^2) y2 - y1.
    type, extends(ode_system_t) :: van_der_pol_t
        real(wp) :: mu = 1000.0_wp
    contains
        procedure :: rhs => vdp_rhs
    end type van_der_pol_t

contains

    subroutine linear_rhs(me, t, y, dydt, stat, errmsg)
        class(linear_stiff_t), intent(inout) :: me
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: dydt(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: a(2, 2)
        me%nevals = me%nevals + 1
        a = reshape([-one, zero, one - me%lambda, -me%lambda], [2, 2])
        dydt = matmul(a, y - [sin(t), cos(t)]) + [cos(t), -sin(t)]
        stat = stat_ok; errmsg = ''
    end subroutine linear_rhs

    subroutine second_rhs(me, t, y, dydt, stat, errmsg)
        class(second_order_stiff_t), intent(inout) :: me
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: dydt(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        me%nevals = me%nevals + 1
        dydt(1) = y(2)
        dydt(2) = -sin(t) + me%c*cos(t) + me%k*sin(t) - me%c*y(2) - me%k*y(1)
        stat = stat_ok; errmsg = ''
    end subroutine second_rhs

    subroutine second_tangent(me, t, y, mass, stiffness, damping, stat, errmsg)
        class(second_order_stiff_t), intent(inout) :: me
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: mass(:, :), stiffness(:, :), damping(:, :)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        mass = one; stiffness = me%k; damping = me%c
        stat = stat_ok; errmsg = ''
    end subroutine second_tangent

    subroutine vdp_rhs(me, t, y, dydt, stat, errmsg)
        class(van_der_pol_t), intent(inout) :: me
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: dydt(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        me%nevals = me%nevals + 1
        dydt(1) = y(2)
        dydt(2) = me%mu*(one - y(1)**2)*y(2) - y(1)
        stat = stat_ok; errmsg = ''
    end subroutine vdp_rhs


    !> y at t_end from y0 with method `name` at a fixed step h (or with
    !! error control at rtol when rtol < loose).
    function solve(name, sys, y0, t_end, h, rtol) result(y)
        character(len=*), intent(in) :: name
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: y0(:), t_end, h, rtol
        real(wp) :: y(size(y0))
        class(integrator_t), allocatable :: integ
        integer :: stat
        character(len=msglen) :: msg
        call new_integrator(name, integ, stat)
        call integ%set_step(h)
        if (rtol >= loose) call integ%set_max_step(h)
        call integ%set_tolerances(rtol, rtol)
        call integ%init(sys, zero, y0, stat, msg)
        call integ%advance(sys, t_end, y, t_end, stat, msg)
#line 119 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 119) )
  if (anyExceptions()) return
#line 120 "/work/main/test/unit/test_stiff_integrators.pf"
    end function solve

    !> Observed order log2(e(h)/e(h/2)) from three step sizes (the last pair).
    real(wp) function observed_order(e) result(p)
        real(wp), intent(in) :: e(3)
        p = log(e(2)/e(3))/log(two)
    end function observed_order

    !@test
    subroutine test_order_linear_stiff_first_order()
        type(linear_stiff_t) :: sys
        real(wp) :: e(3), y(2)
        integer :: k
        do k = 1, 3
            y = solve('ROS34PW2', sys, [zero, one], 1.0_wp, 0.1_wp/2**k, loose)
            e(k) = maxval(abs(y - [sin(1.0_wp), cos(1.0_wp)]))
        end do
#line 137 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(observed_order(e) > 2.7_wp .and. observed_order(e) < 3.5_wp, 'order 3 (dense Jacobian)', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 137) )
  if (anyExceptions()) return
#line 138 "/work/main/test/unit/test_stiff_integrators.pf"
#line 138 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(e(3) < 1.0e-5_wp, 'accurate at h = 0.0125 with h lambda = 125', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 138) )
  if (anyExceptions()) return
#line 139 "/work/main/test/unit/test_stiff_integrators.pf"
    end subroutine test_order_linear_stiff_first_order

    !@test
    subroutine test_order_second_order_structured()
        type(second_order_stiff_t) :: sys
        real(wp) :: e(3), y(2)
        integer :: k
        sys%nsecond = 1
        sys%has_tangent = .true.
        do k = 1, 3
            y = solve('ROS34PW2', sys, [zero, one], 1.0_wp, 0.1_wp/2**k, loose)
            e(k) = maxval(abs(y - [sin(1.0_wp), cos(1.0_wp)]))
        end do
#line 152 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(observed_order(e) > 2.7_wp .and. observed_order(e) < 3.5_wp, 'order 3 (tangent solve)', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 152) )
  if (anyExceptions()) return
#line 153 "/work/main/test/unit/test_stiff_integrators.pf"
    end subroutine test_order_second_order_structured

    !@test
    subroutine test_order_second_order_differences()
        type(second_order_stiff_t) :: sys
        real(wp) :: e(3), y(2)
        integer :: k
        sys%nsecond = 1
        do k = 1, 3
            y = solve('ROS34PW2', sys, [zero, one], 1.0_wp, 0.1_wp/2**k, loose)
            e(k) = maxval(abs(y - [sin(1.0_wp), cos(1.0_wp)]))
        end do
#line 165 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(observed_order(e) > 2.7_wp .and. observed_order(e) < 3.5_wp, 'order 3 (second-order FD solve)', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 165) )
  if (anyExceptions()) return
#line 166 "/work/main/test/unit/test_stiff_integrators.pf"
    end subroutine test_order_second_order_differences

    !@test
    subroutine test_order_van_der_pol()
        type(van_der_pol_t) :: sys
        real(wp) :: e(3), y(2), yref(2)
        integer :: k
        character(len=120) :: msg
        yref = solve('DOPRI5', sys, [two, zero], 0.5_wp, 1.0e-4_wp, 1.0e-12_wp)
        do k = 1, 3
            y = solve('ROS34PW2', sys, [two, zero], 0.5_wp, 0.25_wp/2**k, loose)
            e(k) = maxval(abs(y - yref))
        end do
        write (msg, '(a,3es10.2,a,f6.2)') 'errors ', e, ', observed order ', observed_order(e)
        ! at h mu(1 - y1^2) of 100-800 the order is reduced to about 2, as
        ! expected of Rosenbrock methods on singularly perturbed problems
        ! (Hairer & Wanner VI.3): observed 2.1
#line 183 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(observed_order(e) > 1.8_wp .and. observed_order(e) < 3.6_wp, 'order >= 2 on Van der Pol mu = 1000: '//trim(msg), &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 183) )
  if (anyExceptions()) return
#line 184 "/work/main/test/unit/test_stiff_integrators.pf"
    end subroutine test_order_van_der_pol

    !@test
    subroutine test_error_control_van_der_pol()
        type(van_der_pol_t) :: sys
        real(wp) :: y(2), yref(2), e1, e2
        yref = solve('DOPRI5', sys, [two, zero], 0.5_wp, 1.0e-4_wp, 1.0e-12_wp)
        y = solve('ROS34PW2', sys, [two, zero], 0.5_wp, 1.0e-4_wp, 1.0e-4_wp)
        e1 = maxval(abs(y - yref))
        y = solve('ROS34PW2', sys, [two, zero], 0.5_wp, 1.0e-4_wp, 1.0e-7_wp)
        e2 = maxval(abs(y - yref))
#line 195 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(e1 < 1.0e-2_wp, 'rtol 1e-4: error below 1e-2', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 195) )
  if (anyExceptions()) return
#line 196 "/work/main/test/unit/test_stiff_integrators.pf"
#line 196 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(e1/e2 > 30.0_wp, 'a tolerance 1e3 tighter: error at least 30 times smaller', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 196) )
  if (anyExceptions()) return
#line 197 "/work/main/test/unit/test_stiff_integrators.pf"
    end subroutine test_error_control_van_der_pol

    !@test
    subroutine test_dense_output_and_derivative()
        type(linear_stiff_t) :: sys
        class(integrator_t), allocatable :: integ
        real(wp) :: ym(2), dm(2), tm, t, emax, dmax
        integer :: stat, i
        character(len=msglen) :: msg
        call new_integrator('ROS34PW2', integ, stat)
        call integ%set_step(1.0e-3_wp)
        call integ%set_tolerances(1.0e-6_wp, 1.0e-8_wp)
        call integ%init(sys, zero, [zero, one], stat, msg)
        emax = zero; dmax = zero
        do i = 1, 200
            call integ%step(sys, 2.0_wp, stat, msg)
            t = integ%current_time()
            tm = 0.5_wp*(integ%previous_time() + t)
            call integ%interpolate(tm, ym, dm)
            emax = max(emax, maxval(abs(ym - [sin(tm), cos(tm)])))
            dmax = max(dmax, maxval(abs(dm - [cos(tm), -sin(tm)])))
            if (t >= 2.0_wp) exit
        end do
#line 220 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(emax < 1.0e-5_wp, 'dense output at mid-steps within 1e-5', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 220) )
  if (anyExceptions()) return
#line 221 "/work/main/test/unit/test_stiff_integrators.pf"
#line 221 "/work/main/test/unit/test_stiff_integrators.pf"
  call assertTrue(dmax < 1.0e-3_wp, 'its derivative within 1e-3', &
 & location=SourceLocation( &
 & 'test_stiff_integrators.pf', &
 & 221) )
  if (anyExceptions()) return
#line 222 "/work/main/test/unit/test_stiff_integrators.pf"
    end subroutine test_dense_output_and_derivative

end module test_stiff_integrators

module Wraptest_stiff_integrators
   use FUnit
   use test_stiff_integrators
   implicit none
   private

contains


end module Wraptest_stiff_integrators

function test_stiff_integrators_suite() result(suite)
   use FUnit
   use test_stiff_integrators
   use Wraptest_stiff_integrators
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_stiff_integrators_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_order_linear_stiff_first_order', &
      test_order_linear_stiff_first_order))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_order_second_order_structured', &
      test_order_second_order_structured))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_order_second_order_differences', &
      test_order_second_order_differences))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_order_van_der_pol', &
      test_order_van_der_pol))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_error_control_van_der_pol', &
      test_error_control_van_der_pol))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_dense_output_and_derivative', &
      test_dense_output_and_derivative))
   call suite%addTest(t)


end function test_stiff_integrators_suite

