!> A forced oscillator with a closed-form solution, for the integrator tests.
module test_forced_oscillator
    use hn_kinds, only: wp, pi, msglen
    use hn_ode, only: ode_system_t
    implicit none
    private
    public :: forced_t, exact

    !> y1' = y2, y2' = -w^2 y1 + a sin(nu t), and the quadrature y3' = y2^2.
    type, extends(ode_system_t) :: forced_t
        real(wp) :: w = 2.0_wp*pi, a = 3.0_wp, nu = 5.0_wp
    contains
        procedure :: rhs => forced_rhs
    end type forced_t

contains

    subroutine forced_rhs(me, t, y, dydt, stat, errmsg)
        class(forced_t), intent(inout) :: me
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: dydt(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        stat = 0; errmsg = ''
        me%nevals = me%nevals + 1
        dydt(1) = y(2)
        dydt(2) = -me%w**2*y(1) + me%a*sin(me%nu*t)
        dydt(3) = y(2)**2
    end subroutine forced_rhs

    !> Exact y1, y2 from y1(0) = 1, y2(0) = 0.
    pure function exact(sys, t) result(y)
        type(forced_t), intent(in) :: sys
        real(wp), intent(in) :: t
        real(wp) :: y(2), c, b
        c = sys%a/(sys%w**2 - sys%nu**2)
        b = -c*sys%nu/sys%w
        y(1) = cos(sys%w*t) + b*sin(sys%w*t) + c*sin(sys%nu*t)
        y(2) = -sys%w*sin(sys%w*t) + b*sys%w*cos(sys%w*t) + c*sys%nu*cos(sys%nu*t)
    end function exact

end module test_forced_oscillator

!> Integrators against closed-form solutions: convergence order of the
!! fixed-step methods, tolerance proportionality of the error-controlled
!! ones, accuracy of the dense output between steps, landing on tstop.
program test_integrators
    use hn_kinds, only: wp, zero, one, two, msglen, pi
    use hn_integrators, only: integrator_t, new_integrator
    use hn_testing, only: test_suite_t
    use test_forced_oscillator, only: forced_t, exact
    implicit none

    type(test_suite_t) :: suite
    character(len=8), parameter :: fixed(2) = [character(len=8) :: 'RK4', 'ABM4']
    character(len=8), parameter :: adaptive(3) = [character(len=8) :: 'ADAMS', 'DOPRI5', 'ROS2']
    integer :: k

    do k = 1, size(fixed)
        call test_fixed_order(fixed(k))
    end do
    do k = 1, size(adaptive)
        call test_tolerance(adaptive(k))
    end do
    do k = 1, size(fixed)
        call test_dense_output(fixed(k), 1.0e-6_wp)
    end do
    call test_dense_output('ADAMS', 1.0e-6_wp)
    call test_dense_output('DOPRI5', 1.0e-6_wp)
    call test_dense_output('ROS2', 1.0e-6_wp)
    call test_lands_on_tstop()
    call suite%finish()

contains

    !> Max error of y1, y2 over outputs every 0.01 s to t = 2.
    real(wp) function run_error(name, h, rtol) result(err)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: h, rtol
        class(integrator_t), allocatable :: integ
        type(forced_t) :: sys
        real(wp) :: y(3), t
        integer :: stat, i
        character(len=msglen) :: msg
        sys%nquad = 1
        call new_integrator(name, integ, stat)
        call integ%set_step(h); call integ%set_tolerances(rtol, rtol*1.0e-2_wp)
        call integ%init(sys, zero, [one, zero, zero], stat, msg)
        err = zero
        do i = 1, 200
            t = 0.01_wp*i
            call integ%advance(sys, t, y, huge(one), stat, msg)
            if (stat /= 0) then
                err = huge(one); return
            end if
            err = max(err, maxval(abs(y(1:2) - exact(sys, t))))
        end do
    end function run_error

    !> Halving the step divides the error by 2^4 for these fourth-order methods.
    subroutine test_fixed_order(name)
        character(len=*), intent(in) :: name
        real(wp) :: e1, e2, order
        character(len=100) :: d
        e1 = run_error(name, 2.0e-3_wp, zero)
        e2 = run_error(name, 1.0e-3_wp, zero)
        order = log(e1/e2)/log(two)
        write (d, '(a,es9.2,a,es9.2,a,f5.2)') 'error at h = 2e-3: ', e1, ', 1e-3: ', e2, ', observed order ', order
        call suite%check(abs(order - 4.0_wp) < 0.3_wp, trim(name)//' converges with order 4', d)
    end subroutine test_fixed_order

    !> The global error follows the tolerance. For the fourth/fifth-order
    !! methods it stays below 100 rtol and a tolerance 1e3 times tighter
    !! makes it at least 30 times smaller. ROS2 is of order 2 with error per
    !! step controlled, so its global error grows like rtol^(2/3): 1e3 times
    !! tighter must give 1e3^(2/3) = 100 times smaller, within a factor 2.
    subroutine test_tolerance(name)
        character(len=*), intent(in) :: name
        real(wp) :: e1, e2, r1, r2
        logical :: ok
        character(len=100) :: d
        r1 = 1.0e-4_wp; r2 = 1.0e-7_wp
        if (name == 'ROS2') then
            r1 = 1.0e-3_wp; r2 = 1.0e-6_wp
        end if
        e1 = run_error(name, 1.0e-3_wp, r1)
        e2 = run_error(name, 1.0e-3_wp, r2)
        write (d, '(a,es8.1,a,es9.2,a,es8.1,a,es9.2)') 'rtol ', r1, ': error ', e1, '; rtol ', r2, ': error ', e2
        if (name == 'ROS2') then
            ok = e1/e2 > 50.0_wp .and. e1/e2 < 200.0_wp
        else
            ok = e1 < 100*r1 .and. e2 < 100*r2 .and. e1/e2 > 30.0_wp
        end if
        call suite%check(ok, trim(name)//' error control: error follows the tolerance', d)
    end subroutine test_tolerance

    !> Interpolated values between steps are as accurate as the step ends.
    subroutine test_dense_output(name, rtol)
        character(len=*), intent(in) :: name
        real(wp), intent(in) :: rtol
        class(integrator_t), allocatable :: integ
        type(forced_t) :: sys
        real(wp) :: ym(3), t, ends, mids, tm
        integer :: stat, i
        character(len=msglen) :: msg
        character(len=100) :: d
        sys%nquad = 1
        call new_integrator(name, integ, stat)
        call integ%set_step(2.0e-3_wp); call integ%set_tolerances(rtol, rtol*1.0e-2_wp)
        call integ%init(sys, zero, [one, zero, zero], stat, msg)
        ends = zero; mids = zero
        do i = 1, 400
            call integ%step(sys, huge(one), stat, msg)
            t = integ%current_time()
            ym = integ%current_state()
            ends = max(ends, maxval(abs(ym(1:2) - exact(sys, t))))
            tm = 0.5_wp*(integ%previous_time() + t)
            call integ%interpolate(tm, ym)
            mids = max(mids, maxval(abs(ym(1:2) - exact(sys, tm))))
            if (t > 2.0_wp) exit
        end do
        write (d, '(a,es9.2,a,es9.2)') 'max error at step ends ', ends, ', at mid-steps ', mids
        call suite%check(mids < 5*ends + 1.0e-12_wp, trim(name)//' dense output as accurate as the steps', d)
    end subroutine test_dense_output

    !> Steps end exactly on tstop.
    subroutine test_lands_on_tstop()
        class(integrator_t), allocatable :: integ
        type(forced_t) :: sys
        integer :: stat, k, i
        character(len=msglen) :: msg
        logical :: ok
        character(len=8), parameter :: all(5) = [character(len=8) :: 'RK4', 'ABM4', 'ADAMS', 'DOPRI5', 'ROS2']
        real(wp), parameter :: tstop = 0.123456789_wp
        ok = .true.
        sys%nquad = 1
        do k = 1, size(all)
            call new_integrator(all(k), integ, stat)
            call integ%set_step(1.0e-2_wp); call integ%set_tolerances(1.0e-6_wp, 1.0e-8_wp)
            call integ%init(sys, zero, [one, zero, zero], stat, msg)
            do i = 1, 10000
                call integ%step(sys, tstop, stat, msg)
                if (integ%current_time() >= tstop) exit
            end do
            ok = ok .and. integ%current_time() == tstop
        end do
        call suite%check(ok, 'every integrator ends a step exactly on tstop')
    end subroutine test_lands_on_tstop

end program test_integrators
