!> Integrators of y' = g(t, y) behind one interface. Each type keeps its
!! own state (no module variables): the current point (t, y, f = g(t, y)),
!! the start of the last step (told, yold, fold) and whatever history its
!! formula needs. `step` takes one accepted step that never passes `tstop`
!! (a discontinuity of the inputs lands exactly on a step end);
!! `interpolate` gives y anywhere in the last step (dense output), so
!! output times never constrain the step.
!!
!!   RK4     classical Runge-Kutta, fixed step, Hermite dense output
!!   ABM4    Adams-Bashforth-Moulton 4 PECE, fixed step, started by RK4
!!   ADAMS   variable-step variable-order (1-12) Adams PECE with error
!!           control, Shampine & Gordon's divided-difference formulation
!!   DOPRI5  Dormand-Prince 5(4) with error control and 4th-order dense output
!!   ROS2    linearly implicit Rosenbrock method of order 2 with a 3rd-order
!!           error estimate (Shampine & Reichelt's L-stable pair), Jacobian by
!!           finite differences, for stiff decks
module hn_integrators
    use hn_kinds, only: wp, zero, one, two, half, msglen
    use hn_status, only: stat_bad_input, stat_step_failed, stat_singular
    use hn_ode, only: ode_system_t
    use hn_lapack, only: dgetrf, dgetrs
    implicit none
    private

    public :: integrator_t, rk4_t, abm4_t, adams_t, dopri5_t, ros2_t, new_integrator, spectral_radius

    !> Common state and settings of an integrator.
    type, abstract :: integrator_t
        real(wp) :: h = 1.0e-4_wp       !! fixed step, or first trial step [s]
        real(wp) :: rtol = 1.0e-6_wp    !! relative tolerance (error-controlled methods)
        real(wp) :: atol = 1.0e-8_wp    !! absolute tolerance
        real(wp) :: hmin = 1.0e-12_wp   !! smallest step before giving up [s]
        real(wp) :: hmax = huge(1.0_wp) !! largest step [s]
        real(wp) :: t = zero            !! current time
        real(wp) :: told = zero         !! start of the last step
        real(wp), allocatable :: y(:), f(:), yold(:), fold(:)
        integer :: nsteps = 0           !! accepted steps
        integer :: nreject = 0          !! rejected steps
        integer :: njac = 0             !! Jacobian evaluations
    contains
        procedure :: init => integrator_init
        procedure :: restart => integrator_restart
        procedure :: reset_history => integrator_reset_history
        procedure :: interpolate => hermite_interpolate
        procedure :: advance => integrator_advance
        procedure :: stability_limit => integrator_stability_limit
        procedure(step_interface), deferred :: step
    end type integrator_t

    abstract interface
        !> One accepted step from (t, y), not passing tstop.
        subroutine step_interface(me, sys, tstop, stat, errmsg)
            import :: integrator_t, ode_system_t, wp, msglen
            class(integrator_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys
            real(wp), intent(in) :: tstop
            integer, intent(out) :: stat
            character(len=msglen), intent(out) :: errmsg
        end subroutine step_interface
    end interface

    !> Classical fourth-order Runge-Kutta, fixed step.
    type, extends(integrator_t) :: rk4_t
    contains
        procedure :: step => rk4_step
        procedure :: stability_limit => rk4_stability_limit
    end type rk4_t

    !> Adams-Bashforth-Moulton 4 in PECE mode, fixed step, started by RK4.
    type, extends(integrator_t) :: abm4_t
        real(wp), allocatable :: fh(:, :)   !! f at t-h, t-2h, t-3h
        integer :: nhist = 0
        real(wp) :: hhist = zero           !! step of the history
    contains
        procedure :: step => abm4_step
        procedure :: reset_history => abm4_reset_history
        procedure :: stability_limit => abm4_stability_limit
    end type abm4_t

    !> Dormand-Prince 5(4), error control, dense output.
    type, extends(integrator_t) :: dopri5_t
        real(wp) :: hnext = zero
        real(wp), allocatable :: rcont(:, :)  !! (n, 5) dense-output coefficients of the last step
    contains
        procedure :: step => dopri5_step
        procedure :: interpolate => dopri5_interpolate
        procedure :: reset_history => dopri5_reset_history
    end type dopri5_t

    !> Variable-step, variable-order Adams PECE (Shampine & Gordon).
    type, extends(integrator_t) :: adams_t
        logical :: start = .true., phase1 = .true.
        integer :: k = 1, kold = 0, ns = 0, ifail = 0
        real(wp) :: hs = zero, hold = zero
        real(wp) :: psi(12) = zero, alpha(12) = zero, beta(12) = zero, sig(13) = zero
        real(wp) :: v(12) = zero, w(12) = zero, g(13) = zero
        real(wp), allocatable :: phi(:, :)    !! (n, 16) modified divided differences
        real(wp), allocatable :: wt(:)
    contains
        procedure :: step => adams_step
        procedure :: interpolate => adams_interpolate
        procedure :: reset_history => adams_reset_history
    end type adams_t

    !> Rosenbrock order 2 (3rd-order error estimate), L-stable, FD Jacobian.
    !! The Jacobian is kept for up to `jac_age_max` accepted steps and
    !! recomputed at once after a rejected step.
    type, extends(integrator_t) :: ros2_t
        real(wp) :: hnext = zero
        integer :: jac_age = -1          !! accepted steps since the Jacobian was formed (-1: none)
        integer :: jac_age_max = 5
        real(wp), allocatable :: jac(:, :), wmat(:, :), tdot(:)
        integer, allocatable :: ipiv(:)
    contains
        procedure :: step => ros2_step
        procedure :: reset_history => ros2_reset_history
    end type ros2_t

    ! |gamma*| error constants of the Adams-Moulton formulas (Shampine & Gordon)
    real(wp), parameter :: gstr(13) = [0.500_wp, 0.0833_wp, 0.0417_wp, 0.0264_wp, 0.0188_wp, 0.0143_wp, &
                                       0.0114_wp, 0.00936_wp, 0.00789_wp, 0.00679_wp, 0.00592_wp, &
                                       0.00524_wp, 0.00468_wp]

contains

    !> A new integrator by its deck name (RK4, ABM4, ADAMS, DOPRI5, ROS2);
    !! stat /= 0 for an unknown name.
    subroutine new_integrator(name, integ, stat)
        character(len=*), intent(in) :: name
        class(integrator_t), allocatable, intent(out) :: integ
        integer, intent(out) :: stat
        stat = 0
        select case (name)
        case ('RK4'); allocate (rk4_t :: integ)
        case ('ABM4'); allocate (abm4_t :: integ)
        case ('ADAMS'); allocate (adams_t :: integ)
        case ('DOPRI5'); allocate (dopri5_t :: integ)
        case ('ROS2'); allocate (ros2_t :: integ)
        case default
            stat = stat_bad_input
            allocate (rk4_t :: integ)
        end select
    end subroutine new_integrator

    !> Start at (t0, y0).
    subroutine integrator_init(me, sys, t0, y0, stat, errmsg)
        class(integrator_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: t0, y0(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        me%t = t0
        me%y = y0
        if (allocated(me%f)) deallocate (me%f)
        allocate (me%f(size(y0)))
        call me%restart(sys, stat, errmsg)
    end subroutine integrator_init

    !> Forget the history at the current point (after a discontinuity of
    !! g): recompute f and start the formulas afresh.
    subroutine integrator_restart(me, sys, stat, errmsg)
        class(integrator_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        call sys%rhs(me%t, me%y, me%f, stat, errmsg)
        me%told = me%t
        me%yold = me%y
        me%fold = me%f
        call me%reset_history()
    end subroutine integrator_restart

    !> Methods without history have nothing to reset.
    subroutine integrator_reset_history(me)
        class(integrator_t), intent(inout) :: me
        me%told = me%t
    end subroutine integrator_reset_history

    !> h*rho beyond which the method is unstable (explicit fixed-step
    !! methods); huge for error-controlled methods.
    pure real(wp) function integrator_stability_limit(me) result(r)
        class(integrator_t), intent(in) :: me
        r = huge(1.0_wp) + zero*me%h
    end function integrator_stability_limit

    !> Step until t >= tout (never past tstop) and interpolate y at tout.
    subroutine integrator_advance(me, sys, tout, yout, tstop, stat, errmsg)
        class(integrator_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: tout, tstop
        real(wp), intent(out) :: yout(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        stat = 0; errmsg = ''
        do while (me%t < tout - 1.0e-12_wp*max(one, abs(tout)))
            call me%step(sys, max(tstop, tout), stat, errmsg)
            if (stat /= 0) return
        end do
        call me%interpolate(tout, yout)
    end subroutine integrator_advance

    !> Step size limited so that the step ends exactly on tstop when it
    !! would otherwise pass it or stop just short of it.
    pure real(wp) function clip_step(t, h, tstop) result(hc)
        real(wp), intent(in) :: t, h, tstop
        hc = h
        if (t + 1.01_wp*h >= tstop) hc = tstop - t
    end function clip_step

    !> Accept a step: old point <- current, current <- (tnew, ynew, fnew).
    subroutine accept(me, tnew, ynew, fnew)
        class(integrator_t), intent(inout) :: me
        real(wp), intent(in) :: tnew, ynew(:), fnew(:)
        me%told = me%t
        me%yold = me%y
        me%fold = me%f
        me%t = tnew
        me%y = ynew
        me%f = fnew
        me%nsteps = me%nsteps + 1
    end subroutine accept

    !> Cubic Hermite interpolation between (told, yold, fold) and (t, y, f).
    subroutine hermite_interpolate(me, tout, yout)
        class(integrator_t), intent(in) :: me
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: yout(:)
        real(wp) :: h, s, h00, h10, h01, h11
        h = me%t - me%told
        if (h <= zero .or. tout >= me%t) then
            yout = me%y
            return
        end if
        s = (tout - me%told)/h
        h00 = (one + two*s)*(one - s)**2
        h10 = s*(one - s)**2
        h01 = s**2*(3.0_wp - two*s)
        h11 = s**2*(s - one)
        yout = h00*me%yold + h10*h*me%fold + h01*me%y + h11*h*me%f
    end subroutine hermite_interpolate

    !> Weighted RMS norm of e with weights atol + rtol max(|y0|, |y1|).
    pure real(wp) function err_norm(me, e, y0, y1) result(r)
        class(integrator_t), intent(in) :: me
        real(wp), intent(in) :: e(:), y0(:), y1(:)
        r = sqrt(sum((e/(me%atol + me%rtol*max(abs(y0), abs(y1))))**2)/size(e))
    end function err_norm

    ! ------------------------------------------------------------------ RK4

    subroutine rk4_step(me, sys, tstop, stat, errmsg)
        class(rk4_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: tstop
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp), dimension(size(me%y)) :: k2, k3, k4, ynew, fnew
        real(wp) :: h
        h = clip_step(me%t, me%h, tstop)
        call rk4_formula(sys, me%t, me%y, me%f, h, ynew, k2, k3, k4, stat, errmsg)
        if (stat /= 0) return
        call sys%rhs(me%t + h, ynew, fnew, stat, errmsg)
        if (stat /= 0) return
        call accept(me, me%t + h, ynew, fnew)
    end subroutine rk4_step

    !> One RK4 step of size h from (t, y) with f = g(t, y) given.
    subroutine rk4_formula(sys, t, y, f, h, ynew, k2, k3, k4, stat, errmsg)
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: t, y(:), f(:), h
        real(wp), intent(out) :: ynew(:), k2(:), k3(:), k4(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        call sys%rhs(t + half*h, y + half*h*f, k2, stat, errmsg); if (stat /= 0) return
        call sys%rhs(t + half*h, y + half*h*k2, k3, stat, errmsg); if (stat /= 0) return
        call sys%rhs(t + h, y + h*k3, k4, stat, errmsg); if (stat /= 0) return
        ynew = y + h/6.0_wp*(f + two*k2 + two*k3 + k4)
    end subroutine rk4_formula

    !> RK4 is stable for h |lambda| up to about 2.78 on the negative real axis.
    pure real(wp) function rk4_stability_limit(me) result(r)
        class(rk4_t), intent(in) :: me
        r = 2.78_wp + zero*me%h
    end function rk4_stability_limit

    ! ------------------------------------------------------------------ ABM4

    subroutine abm4_reset_history(me)
        class(abm4_t), intent(inout) :: me
        me%nhist = 0
        if (.not. allocated(me%fh)) allocate (me%fh(size(me%y), 3))
    end subroutine abm4_reset_history

    subroutine abm4_step(me, sys, tstop, stat, errmsg)
        class(abm4_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: tstop
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp), dimension(size(me%y)) :: k2, k3, k4, yp, fp, yc, fc
        real(wp) :: h
        h = clip_step(me%t, me%h, tstop)
        if (h /= me%hhist) me%nhist = 0          ! history of another step size is useless
        me%hhist = h
        if (me%nhist < 3) then
            ! start (and restart) with RK4
            call rk4_formula(sys, me%t, me%y, me%f, h, yc, k2, k3, k4, stat, errmsg)
            if (stat /= 0) return
        else
            ! predict (Adams-Bashforth 4), evaluate, correct (Adams-Moulton 4), evaluate
            yp = me%y + h/24.0_wp*(55.0_wp*me%f - 59.0_wp*me%fh(:, 1) + 37.0_wp*me%fh(:, 2) - 9.0_wp*me%fh(:, 3))
            call sys%rhs(me%t + h, yp, fp, stat, errmsg)
            if (stat /= 0) return
            yc = me%y + h/24.0_wp*(9.0_wp*fp + 19.0_wp*me%f - 5.0_wp*me%fh(:, 1) + me%fh(:, 2))
        end if
        call sys%rhs(me%t + h, yc, fc, stat, errmsg)
        if (stat /= 0) return
        me%fh(:, 3) = me%fh(:, 2)
        me%fh(:, 2) = me%fh(:, 1)
        me%fh(:, 1) = me%f
        me%nhist = min(3, me%nhist + 1)
        call accept(me, me%t + h, yc, fc)
    end subroutine abm4_step

    !> ABM4 PECE: real stability interval about (-1.3, 0); take 1.2.
    pure real(wp) function abm4_stability_limit(me) result(r)
        class(abm4_t), intent(in) :: me
        r = 1.2_wp + zero*me%h
    end function abm4_stability_limit

    ! ------------------------------------------------------------------ DOPRI5

    subroutine dopri5_reset_history(me)
        class(dopri5_t), intent(inout) :: me
        if (.not. allocated(me%rcont)) allocate (me%rcont(size(me%y), 5))
        me%rcont = zero
        me%rcont(:, 1) = me%y
        if (me%hnext <= zero) me%hnext = me%h
    end subroutine dopri5_reset_history

    subroutine dopri5_step(me, sys, tstop, stat, errmsg)
        class(dopri5_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: tstop
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
        ! dense output of Shampine (1986)
        real(wp), parameter :: d1 = -12715105075.0_wp/11282082432.0_wp, d3 = 87487479700.0_wp/32700410799.0_wp, &
                               d4 = -10690763975.0_wp/1880347072.0_wp, d5 = 701980252875.0_wp/199316789632.0_wp, &
                               d6 = -1453857185.0_wp/822651844.0_wp, d7 = 69997945.0_wp/29380423.0_wp
        real(wp), dimension(size(me%y)) :: k1, k2, k3, k4, k5, k6, k7, ynew, ytmp
        real(wp) :: h, err, fac
        stat = 0; errmsg = ''
        k1 = me%f
        do
            h = clip_step(me%t, min(me%hnext, me%hmax), tstop)
            ytmp = me%y + h*a21*k1
            call sys%rhs(me%t + c2*h, ytmp, k2, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a31*k1 + a32*k2)
            call sys%rhs(me%t + c3*h, ytmp, k3, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a41*k1 + a42*k2 + a43*k3)
            call sys%rhs(me%t + c4*h, ytmp, k4, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a51*k1 + a52*k2 + a53*k3 + a54*k4)
            call sys%rhs(me%t + c5*h, ytmp, k5, stat, errmsg); if (stat /= 0) return
            ytmp = me%y + h*(a61*k1 + a62*k2 + a63*k3 + a64*k4 + a65*k5)
            call sys%rhs(me%t + h, ytmp, k6, stat, errmsg); if (stat /= 0) return
            ynew = me%y + h*(b1*k1 + b3*k3 + b4*k4 + b5*k5 + b6*k6)
            call sys%rhs(me%t + h, ynew, k7, stat, errmsg); if (stat /= 0) return
            err = max(err_norm(me, h*(e1*k1 + e3*k3 + e4*k4 + e5*k5 + e6*k6 + e7*k7), me%y, ynew), 1.0e-10_wp)
            if (err <= one) exit
            me%nreject = me%nreject + 1
            me%hnext = h*max(0.2_wp, 0.9_wp*err**(-0.2_wp))
            if (me%hnext < me%hmin) then
                call step_too_small(me%t, me%hmin, stat, errmsg)
                return
            end if
        end do
        me%rcont(:, 1) = me%y
        me%rcont(:, 2) = ynew - me%y
        me%rcont(:, 3) = h*k1 - me%rcont(:, 2)
        me%rcont(:, 4) = me%rcont(:, 2) - h*k7 - me%rcont(:, 3)
        me%rcont(:, 5) = h*(d1*k1 + d3*k3 + d4*k4 + d5*k5 + d6*k6 + d7*k7)
        fac = min(5.0_wp, max(0.2_wp, 0.9_wp*err**(-0.2_wp)))
        if (h >= me%hnext*0.999_wp .or. fac < one) me%hnext = h*fac   ! a clipped step does not shrink hnext
        call accept(me, me%t + h, ynew, k7)
    end subroutine dopri5_step

    subroutine dopri5_interpolate(me, tout, yout)
        class(dopri5_t), intent(in) :: me
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: yout(:)
        real(wp) :: s, s1, h
        h = me%t - me%told
        if (h <= zero .or. tout >= me%t) then
            yout = me%y
            return
        end if
        s = (tout - me%told)/h
        s1 = one - s
        yout = me%rcont(:, 1) + s*(me%rcont(:, 2) + s1*(me%rcont(:, 3) + s*(me%rcont(:, 4) + s1*me%rcont(:, 5))))
    end subroutine dopri5_interpolate

    subroutine step_too_small(t, hmin, stat, errmsg)
        real(wp), intent(in) :: t, hmin
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        stat = stat_step_failed
        write (errmsg, '(a,es10.3,a,es12.5,a)') 'the step fell below ', hmin, ' s at t = ', t, &
            ' s: the deck may be too stiff for this method (try ROS2) or the tolerance too tight'
    end subroutine step_too_small

    ! ------------------------------------------------------------------ ADAMS

    subroutine adams_reset_history(me)
        class(adams_t), intent(inout) :: me
        integer :: n
        n = size(me%y)
        if (.not. allocated(me%phi)) allocate (me%phi(n, 16), me%wt(n))
        me%start = .true.
        me%phi = zero
    end subroutine adams_reset_history

    !> One step of the variable-order Adams PECE method in the modified
    !! divided-difference form of Shampine & Gordon (1975), with local
    !! error control in the weighted RMS norm and order selection 1-12.
    subroutine adams_step(me, sys, tstop, stat, errmsg)
        class(adams_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: tstop
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp), dimension(size(me%y)) :: p, yp, ynew
        real(wp) :: absh, erk, erkm1, erkm2, erkp1, err, temp1, temp2, temp3, temp4, temp5, temp6, &
                    r, hnew, reali, hwant, eps
        integer :: i, iq, j, kp1, kp2, km1, km2, nsp1, nsp2, limit1, limit2, knew, im1, n, l
        real(wp), parameter :: two_pow(13) = [2.0_wp, 4.0_wp, 8.0_wp, 16.0_wp, 32.0_wp, 64.0_wp, 128.0_wp, &
                                              256.0_wp, 512.0_wp, 1024.0_wp, 2048.0_wp, 4096.0_wp, 8192.0_wp]
        stat = 0; errmsg = ''
        n = size(me%y)
        eps = one                               ! errors are measured against the weights wt
        me%wt = me%atol + me%rtol*abs(me%y)
        if (me%start) then
            me%phi(:, 1) = me%f
            me%phi(:, 2) = zero
            temp1 = sqrt(sum((me%f/me%wt)**2)/n)
            absh = min(me%h, me%hmax)
            if (eps < 16.0_wp*temp1*absh**2) absh = 0.25_wp*sqrt(eps/temp1)
            me%hs = max(absh, me%hmin)
            me%hold = zero; me%k = 1; me%kold = 0; me%start = .false.; me%phase1 = .true.
            me%ns = 0; me%ifail = 0
            me%g(1) = one; me%g(2) = half; me%sig(1) = one
        end if
        hwant = me%hs
        ! land on tstop: a step that would pass it is shortened (the formula
        ! coefficients follow any step size, so nothing else changes)
        if (me%t + 1.01_wp*me%hs >= tstop) me%hs = tstop - me%t
        do
            ! block 1: coefficients for this step
            kp1 = me%k + 1; kp2 = me%k + 2; km1 = me%k - 1; km2 = me%k - 2
            if (me%hs /= me%hold) me%ns = 0
            if (me%ns <= me%kold) me%ns = me%ns + 1
            nsp1 = me%ns + 1
            if (me%k >= me%ns) then
                me%beta(me%ns) = one
                me%alpha(me%ns) = one/me%ns
                temp1 = me%hs*me%ns
                me%sig(nsp1) = one
                if (me%k >= nsp1) then
                    do i = nsp1, me%k
                        im1 = i - 1
                        temp2 = me%psi(im1)
                        me%psi(im1) = temp1
                        me%beta(i) = me%beta(im1)*me%psi(im1)/temp2
                        temp1 = temp2 + me%hs
                        me%alpha(i) = me%hs/temp1
                        reali = i
                        me%sig(i + 1) = reali*me%alpha(i)*me%sig(i)
                    end do
                end if
                me%psi(me%k) = temp1
                if (me%ns <= 1) then
                    do iq = 1, me%k
                        me%v(iq) = one/(iq*(iq + 1))
                        me%w(iq) = me%v(iq)
                    end do
                else
                    if (me%k > me%kold) then
                        me%v(me%k) = one/(me%k*kp1)
                        do j = 1, me%ns - 2
                            i = me%k - j
                            me%v(i) = me%v(i) - me%alpha(j + 1)*me%v(i + 1)
                        end do
                    end if
                    limit1 = kp1 - me%ns
                    temp5 = me%alpha(me%ns)
                    do iq = 1, limit1
                        me%v(iq) = me%v(iq) - temp5*me%v(iq + 1)
                        me%w(iq) = me%v(iq)
                    end do
                    me%g(nsp1) = me%w(1)
                end if
                nsp2 = me%ns + 2
                if (kp1 >= nsp2) then
                    do i = nsp2, kp1
                        limit2 = kp2 - i
                        temp6 = me%alpha(i - 1)
                        do iq = 1, limit2
                            me%w(iq) = me%w(iq) - temp6*me%w(iq + 1)
                        end do
                        me%g(i) = me%w(1)
                    end do
                end if
            end if

            ! block 2: predict, evaluate, estimate the local error at orders k, k-1, k-2
            if (me%k >= nsp1) then
                do i = nsp1, me%k
                    me%phi(:, i) = me%beta(i)*me%phi(:, i)
                end do
            end if
            me%phi(:, kp2) = me%phi(:, kp1)
            me%phi(:, kp1) = zero
            p = zero
            do j = 1, me%k
                i = kp1 - j
                p = p + me%g(i)*me%phi(:, i)
                me%phi(:, i) = me%phi(:, i) + me%phi(:, i + 1)
            end do
            p = me%y + me%hs*p
            call sys%rhs(me%t + me%hs, p, yp, stat, errmsg)
            if (stat /= 0) return
            absh = abs(me%hs)
            erkm2 = zero; erkm1 = zero; erk = zero
            do l = 1, n
                temp3 = one/me%wt(l)
                temp4 = yp(l) - me%phi(l, 1)
                if (km2 > 0) erkm2 = erkm2 + ((me%phi(l, km1) + temp4)*temp3)**2
                if (km2 >= 0) erkm1 = erkm1 + ((me%phi(l, me%k) + temp4)*temp3)**2
                erk = erk + (temp4*temp3)**2
            end do
            erkm2 = sqrt(erkm2/n); erkm1 = sqrt(erkm1/n); erk = sqrt(erk/n)
            if (km2 > 0) erkm2 = absh*me%sig(km1)*gstr(km2)*erkm2
            if (km2 >= 0) erkm1 = absh*me%sig(me%k)*gstr(km1)*erkm1
            temp5 = absh*erk
            err = temp5*(me%g(me%k) - me%g(kp1))
            erk = temp5*me%sig(kp1)*gstr(me%k)
            knew = me%k
            if (km2 > 0) then
                if (max(erkm1, erkm2) <= erk) knew = km1
            else if (km2 == 0) then
                if (erkm1 <= half*erk) knew = km1
            end if
            if (err <= eps) exit

            ! block 3: the step failed; restore and retry with a smaller step
            me%phase1 = .false.
            me%nreject = me%nreject + 1
            do i = 1, me%k
                temp1 = one/me%beta(i)
                me%phi(:, i) = temp1*(me%phi(:, i) - me%phi(:, i + 1))
            end do
            do i = 2, me%k
                me%psi(i - 1) = me%psi(i) - me%hs
            end do
            me%ifail = me%ifail + 1
            temp2 = half
            if (me%ifail > 3 .and. half*eps < 0.25_wp*erk) temp2 = sqrt(half*eps/erk)
            if (me%ifail >= 3) knew = 1
            me%hs = temp2*me%hs
            me%k = knew
            if (me%hs < me%hmin) then
                call step_too_small(me%t, me%hmin, stat, errmsg)
                return
            end if
        end do

        ! block 4: the step succeeded; correct, evaluate, update the differences
        me%kold = me%k
        me%hold = me%hs
        temp1 = me%hs*me%g(kp1)
        ynew = p + temp1*(yp - me%phi(:, 1))
        call sys%rhs(me%t + me%hs, ynew, yp, stat, errmsg)
        if (stat /= 0) return
        me%phi(:, kp1) = yp - me%phi(:, 1)
        me%phi(:, kp2) = me%phi(:, kp1) - me%phi(:, kp2)
        do i = 1, me%k
            me%phi(:, i) = me%phi(:, i) + me%phi(:, kp1)
        end do
        call accept(me, me%t + me%hs, ynew, yp)
        me%ifail = 0

        ! order for the next step
        erkp1 = zero
        if (knew == km1 .or. me%k == 12) me%phase1 = .false.
        if (me%phase1) then
            me%k = kp1; erk = erkp1
        else if (knew == km1) then
            me%k = km1; erk = erkm1
        else if (kp1 <= me%ns) then
            erkp1 = absh*gstr(kp1)*sqrt(sum((me%phi(:, kp2)/me%wt)**2)/n)
            if (me%k > 1) then
                if (erkm1 <= min(erk, erkp1)) then
                    me%k = km1; erk = erkm1
                else if (erkp1 < erk .and. me%k /= 12) then
                    me%k = kp1; erk = erkp1
                end if
            else if (erkp1 < half*erk) then
                me%k = kp1; erk = erkp1
            end if
        end if

        ! step size for the next step
        if (me%phase1 .or. half*eps >= erk*two_pow(me%k + 1)) then
            hnew = two*me%hs
        else if (half*eps >= erk) then
            hnew = me%hs
        else
            r = (half*eps/erk)**(one/(me%k + 1))
            hnew = absh*max(half, min(0.9_wp, r))
        end if
        ! a step shortened to land on tstop does not shrink the next one
        if (me%hs < hwant .and. hnew < hwant) hnew = min(hwant, two*me%hs)
        me%hs = min(max(hnew, me%hmin), me%hmax)
    end subroutine adams_step

    !> Shampine & Gordon's interpolation from the divided differences of the
    !! last step (order kold).
    subroutine adams_interpolate(me, tout, yout)
        class(adams_t), intent(in) :: me
        real(wp), intent(in) :: tout
        real(wp), intent(out) :: yout(:)
        real(wp) :: hi, term, gamma, eta, psijm1, gi(13), wi(13)
        integer :: i, j, ki, kip1, limit1
        if (me%t - me%told <= zero .or. tout >= me%t) then
            yout = me%y
            return
        end if
        hi = tout - me%t
        ki = me%kold + 1
        kip1 = ki + 1
        do i = 1, ki
            wi(i) = one/i
        end do
        term = zero
        gi(1) = one
        do j = 2, ki
            psijm1 = me%psi(j - 1)
            gamma = (hi + term)/psijm1
            eta = hi/psijm1
            limit1 = kip1 - j
            do i = 1, limit1
                wi(i) = gamma*wi(i) - eta*wi(i + 1)
            end do
            gi(j) = wi(1)
            term = psijm1
        end do
        yout = zero
        do j = 1, ki
            i = kip1 - j
            yout = yout + gi(i)*me%phi(:, i)
        end do
        yout = me%y + hi*yout
    end subroutine adams_interpolate

    ! ------------------------------------------------------------------ ROS2

    subroutine ros2_reset_history(me)
        class(ros2_t), intent(inout) :: me
        integer :: n
        n = size(me%y)
        if (.not. allocated(me%jac)) then
            allocate (me%jac(n, n), me%wmat(n, n), me%ipiv(n), me%tdot(n))
            me%jac_age = -1
        end if
        ! a restart at a kink of the inputs keeps the Jacobian: it changes little there
        if (me%hnext <= zero) me%hnext = me%h
    end subroutine ros2_reset_history

    !> Jacobian and time derivative of g at the current point.
    subroutine ros2_jacobian(me, sys, stat, errmsg)
        class(ros2_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: dt, ft(size(me%y))
        call fd_jacobian(sys, me%t, me%y, me%f, me%jac, stat, errmsg)
        if (stat /= 0) return
        dt = sqrt(epsilon(one))*max(abs(me%t), 1.0e-3_wp)
        call sys%rhs(me%t + dt, me%y, ft, stat, errmsg)
        if (stat /= 0) return
        me%tdot = (ft - me%f)/dt
        me%njac = me%njac + 1
        me%jac_age = 0
    end subroutine ros2_jacobian

    !> Jacobian dg/dy by forward differences (quadrature columns are zero).
    subroutine fd_jacobian(sys, t, y, f, jac, stat, errmsg)
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: t, y(:), f(:)
        real(wp), intent(out) :: jac(:, :)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: yp(size(y)), fp(size(y)), d
        integer :: j
        stat = 0
        jac = zero
        yp = y
        do j = 1, size(y) - sys%nquad
            d = sqrt(epsilon(one))*max(abs(y(j)), 1.0e-4_wp)
            yp(j) = y(j) + d
            call sys%rhs(t, yp, fp, stat, errmsg)
            if (stat /= 0) return
            jac(:, j) = (fp - f)/d
            yp(j) = y(j)
        end do
    end subroutine fd_jacobian

    !> One step of the L-stable Rosenbrock pair of Shampine & Reichelt
    !! (MATLAB's ode23s): d = 1/(2 + sqrt 2), W = I - h d J,
    !!   k1 = W^-1 (F0 + h d T), F1 = g(t + h/2, y + h k1/2)
    !!   k2 = W^-1 (F1 - k1) + k1, ynew = y + h k2, F2 = g(t + h, ynew)
    !!   k3 = W^-1 (F2 - e32 (k2 - F1) - 2 (k1 - F0) + h d T)
    !!   error = h (k1 - 2 k2 + k3) / 6
    !! with T = dg/dt by a forward difference.
    subroutine ros2_step(me, sys, tstop, stat, errmsg)
        class(ros2_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: tstop
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp), parameter :: d = one/(two + sqrt(two)), e32 = 6.0_wp + sqrt(two)
        real(wp), dimension(size(me%y)) :: k1, k2, k3, f1, f2, ynew
        real(wp) :: h, err
        integer :: n, i, info
        stat = 0; errmsg = ''
        n = size(me%y)
        if (me%jac_age < 0 .or. me%jac_age >= me%jac_age_max) then
            call ros2_jacobian(me, sys, stat, errmsg)
            if (stat /= 0) return
        end if
        do
            h = clip_step(me%t, min(me%hnext, me%hmax), tstop)
            me%wmat = -h*d*me%jac
            do i = 1, n
                me%wmat(i, i) = me%wmat(i, i) + one
            end do
            call dgetrf(n, n, me%wmat, n, me%ipiv, info)
            if (info /= 0) then
                stat = stat_singular
                write (errmsg, '(a,es12.5,a)') 'ROS2: the iteration matrix I - h d J is singular at t = ', me%t, ' s'
                return
            end if
            k1 = me%f + h*d*me%tdot
            call lu_solve(k1)
            call sys%rhs(me%t + half*h, me%y + half*h*k1, f1, stat, errmsg)
            if (stat /= 0) return
            k2 = f1 - k1
            call lu_solve(k2)
            k2 = k2 + k1
            ynew = me%y + h*k2
            call sys%rhs(me%t + h, ynew, f2, stat, errmsg)
            if (stat /= 0) return
            k3 = f2 - e32*(k2 - f1) - two*(k1 - me%f) + h*d*me%tdot
            call lu_solve(k3)
            err = max(err_norm(me, h/6.0_wp*(k1 - two*k2 + k3), me%y, ynew), 1.0e-10_wp)
            if (err <= one) exit
            me%nreject = me%nreject + 1
            me%hnext = h*max(0.2_wp, 0.8_wp*err**(-one/3.0_wp))
            if (me%hnext < me%hmin) then
                call step_too_small(me%t, me%hmin, stat, errmsg)
                return
            end if
            if (me%jac_age > 0) then
                ! an aged Jacobian may be the cause: form a fresh one
                call ros2_jacobian(me, sys, stat, errmsg)
                if (stat /= 0) return
            end if
        end do
        me%jac_age = me%jac_age + 1
        if (h >= me%hnext*0.999_wp .or. err > 0.5_wp) me%hnext = h*min(5.0_wp, max(0.2_wp, 0.8_wp*err**(-one/3.0_wp)))
        call accept(me, me%t + h, ynew, f2)
    contains
        subroutine lu_solve(b)
            real(wp), intent(inout) :: b(:)
            integer :: inf
            call dgetrs('N', n, 1, me%wmat, n, me%ipiv, b, n, inf)
        end subroutine lu_solve
    end subroutine ros2_step

    ! ------------------------------------------------------------------ stability

    !> Estimate of the spectral radius of dg/dy at (t, y) by power iteration
    !! on finite-difference Jacobian-vector products; `lead` is the
    !! component with the largest entry of the dominant eigenvector.
    subroutine spectral_radius(sys, t, y, rho, lead, stat, errmsg)
        class(ode_system_t), intent(inout) :: sys
        real(wp), intent(in) :: t, y(:)
        real(wp), intent(out) :: rho
        integer, intent(out) :: lead
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        real(wp) :: f0(size(y)), f1(size(y)), v(size(y)), u(size(y)), d, nv
        integer :: it, n, j
        n = size(y) - sys%nquad
        call sys%rhs(t, y, f0, stat, errmsg)
        if (stat /= 0) return
        do j = 1, size(y)
            v(j) = one + 0.1_wp*sin(real(7*j, wp))
        end do
        v(n + 1:) = zero
        v = v/norm2(v)
        rho = zero
        lead = 1
        do it = 1, 40
            d = sqrt(epsilon(one))*max(one, norm2(y(1:n)))
            call sys%rhs(t, y + d*v, f1, stat, errmsg)
            if (stat /= 0) return
            u = (f1 - f0)/d
            u(n + 1:) = zero
            nv = norm2(u)
            if (nv == zero) exit
            rho = nv
            v = u/nv
        end do
        lead = maxloc(abs(v(1:n)), dim=1)
    end subroutine spectral_radius

end module hn_integrators
