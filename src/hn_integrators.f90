!> Integrators of y' = g(t, y) behind one interface: each type advances the
!! state from t to a requested output time, landing on it exactly.
module hn_integrators
    use hn_kinds, only: wp, zero, one, msglen
    use hn_ode, only: ode_system_t
    implicit none
    private

    public :: integrator_t, rk4_t, dopri5_t

    !> Common state of an integrator.
    type, abstract :: integrator_t
        real(wp) :: h = 1.0e-4_wp      !! fixed step, or first trial step [s]
        real(wp) :: rtol = 1.0e-6_wp   !! relative tolerance (error-controlled methods)
        real(wp) :: atol = 1.0e-8_wp   !! absolute tolerance
        real(wp) :: hmin = 1.0e-12_wp  !! smallest step before giving up [s]
        integer :: nsteps = 0          !! accepted steps
        integer :: nreject = 0         !! rejected steps
    contains
        procedure(advance_interface), deferred :: advance
        procedure :: restart => integrator_restart
    end type integrator_t

    abstract interface
        !> Advance (t, y) to tout; stat /= 0 with errmsg on failure.
        subroutine advance_interface(me, sys, t, y, tout, stat, errmsg)
            import :: integrator_t, ode_system_t, wp, msglen
            class(integrator_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys
            real(wp), intent(inout) :: t
            real(wp), intent(inout) :: y(:)
            real(wp), intent(in) :: tout
            integer, intent(out) :: stat
            character(len=msglen), intent(out) :: errmsg
        end subroutine advance_interface
    end interface

    !> Classical fourth-order Runge-Kutta with fixed step h.
    type, extends(integrator_t) :: rk4_t
    contains
        procedure :: advance => rk4_advance
    end type rk4_t

    !> Dormand-Prince 5(4) with error control (FSAL).
    type, extends(integrator_t) :: dopri5_t
        real(wp) :: hnext = zero
        logical :: have_k1 = .false.
        real(wp), allocatable :: k1(:)
    contains
        procedure :: advance => dopri5_advance
        procedure :: restart => dopri5_restart
    end type dopri5_t

contains

    !> Forget history (after a discontinuity); no-op for one-step methods.
    subroutine integrator_restart(me)
        class(integrator_t), intent(inout) :: me
        ! one-step methods carry no history between calls
    end subroutine integrator_restart

    subroutine rk4_advance(me, sys, t, y, tout, stat, errmsg)
        class(rk4_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(inout) :: t
        real(wp), intent(inout) :: y(:)
        real(wp), intent(in) :: tout
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: k1(size(y)), k2(size(y)), k3(size(y)), k4(size(y)), h, t0
        integer :: nsub, i
        stat = 0; errmsg = ''
        if (tout <= t) return
        nsub = max(1, ceiling((tout - t)/me%h*(one - 1.0e-12_wp)))
        h = (tout - t)/nsub
        t0 = t
        do i = 1, nsub
            call sys%rhs(t, y, k1, stat, errmsg); if (stat /= 0) return
            call sys%rhs(t + 0.5_wp*h, y + 0.5_wp*h*k1, k2, stat, errmsg); if (stat /= 0) return
            call sys%rhs(t + 0.5_wp*h, y + 0.5_wp*h*k2, k3, stat, errmsg); if (stat /= 0) return
            call sys%rhs(t + h, y + h*k3, k4, stat, errmsg); if (stat /= 0) return
            y = y + h/6.0_wp*(k1 + 2.0_wp*k2 + 2.0_wp*k3 + k4)
            t = t0 + i*h
            me%nsteps = me%nsteps + 1
        end do
        t = tout
    end subroutine rk4_advance

    subroutine dopri5_restart(me)
        class(dopri5_t), intent(inout) :: me
        me%have_k1 = .false.
    end subroutine dopri5_restart

    subroutine dopri5_advance(me, sys, t, y, tout, stat, errmsg)
        class(dopri5_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(inout) :: t
        real(wp), intent(inout) :: y(:)
        real(wp), intent(in) :: tout
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp), parameter :: c2 = 1.0_wp/5, c3 = 3.0_wp/10, c4 = 4.0_wp/5, c5 = 8.0_wp/9
        real(wp), parameter :: a21 = 1.0_wp/5
        real(wp), parameter :: a31 = 3.0_wp/40, a32 = 9.0_wp/40
        real(wp), parameter :: a41 = 44.0_wp/45, a42 = -56.0_wp/15, a43 = 32.0_wp/9
        real(wp), parameter :: a51 = 19372.0_wp/6561, a52 = -25360.0_wp/2187, a53 = 64448.0_wp/6561, &
                               a54 = -212.0_wp/729
        real(wp), parameter :: a61 = 9017.0_wp/3168, a62 = -355.0_wp/33, a63 = 46732.0_wp/5247, &
                               a64 = 49.0_wp/176, a65 = -5103.0_wp/18656
        real(wp), parameter :: b1 = 35.0_wp/384, b3 = 500.0_wp/1113, b4 = 125.0_wp/192, &
                               b5 = -2187.0_wp/6784, b6 = 11.0_wp/84
        real(wp), parameter :: e1 = 71.0_wp/57600, e3 = -71.0_wp/16695, e4 = 71.0_wp/1920, &
                               e5 = -17253.0_wp/339200, e6 = 22.0_wp/525, e7 = -1.0_wp/40
        real(wp), dimension(size(y)) :: k2, k3, k4, k5, k6, k7, ynew, ytmp, sc
        real(wp) :: h, err, fac
        logical :: last
        stat = 0; errmsg = ''
        if (tout <= t) return
        if (.not. allocated(me%k1)) allocate (me%k1(size(y)))
        if (.not. me%have_k1) then
            call sys%rhs(t, y, me%k1, stat, errmsg); if (stat /= 0) return
            me%have_k1 = .true.
        end if
        if (me%hnext <= zero) me%hnext = me%h
        do
            h = me%hnext
            last = .false.
            if (t + h >= tout - 1.0e-12_wp*abs(tout)) then
                h = tout - t
                last = .true.
            end if
            ytmp = y + h*a21*me%k1
            call sys%rhs(t + c2*h, ytmp, k2, stat, errmsg); if (stat /= 0) return
            ytmp = y + h*(a31*me%k1 + a32*k2)
            call sys%rhs(t + c3*h, ytmp, k3, stat, errmsg); if (stat /= 0) return
            ytmp = y + h*(a41*me%k1 + a42*k2 + a43*k3)
            call sys%rhs(t + c4*h, ytmp, k4, stat, errmsg); if (stat /= 0) return
            ytmp = y + h*(a51*me%k1 + a52*k2 + a53*k3 + a54*k4)
            call sys%rhs(t + c5*h, ytmp, k5, stat, errmsg); if (stat /= 0) return
            ytmp = y + h*(a61*me%k1 + a62*k2 + a63*k3 + a64*k4 + a65*k5)
            call sys%rhs(t + h, ytmp, k6, stat, errmsg); if (stat /= 0) return
            ynew = y + h*(b1*me%k1 + b3*k3 + b4*k4 + b5*k5 + b6*k6)
            call sys%rhs(t + h, ynew, k7, stat, errmsg); if (stat /= 0) return
            sc = me%atol + me%rtol*max(abs(y), abs(ynew))
            err = sqrt(sum((h*(e1*me%k1 + e3*k3 + e4*k4 + e5*k5 + e6*k6 + e7*k7)/sc)**2)/size(y))
            err = max(err, 1.0e-10_wp)
            if (err <= one) then
                t = t + h
                if (last) t = tout
                y = ynew
                me%k1 = k7
                me%nsteps = me%nsteps + 1
                fac = min(5.0_wp, max(0.2_wp, 0.9_wp*err**(-0.2_wp)))
                if (.not. last .or. fac < one) me%hnext = h*fac
                if (last) return
            else
                me%nreject = me%nreject + 1
                fac = max(0.2_wp, 0.9_wp*err**(-0.2_wp))
                me%hnext = h*fac
                if (me%hnext < me%hmin) then
                    stat = 1
                    write (errmsg, '(a,es10.3,a,es10.3,a)') 'step size fell below ', me%hmin, &
                        ' s at t = ', t, ' s; the problem may be stiff or the tolerance too tight'
                    return
                end if
            end if
        end do
    end subroutine dopri5_advance

end module hn_integrators
