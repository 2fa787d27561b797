!> Integrators of y' = g(t, y) behind one interface. Each type keeps its
!! own state (no module variables, components private): the current point
!! (t, y, f = g(t, y)), the start of the last step (told, yold, fold) and
!! whatever history its formula needs. `step` takes one accepted step that
!! never passes `tstop` (a discontinuity of the inputs lands exactly on a
!! step end); `interpolate` gives y, and on request y', anywhere in the
!! last step (dense output), so output times never constrain the step.
!! `interpolate_hermite` gives the cubic Hermite interpolant of the last step's
!! end points (y and f = g(t, y) at both) for every method: its derivative
!! is what the run's output path uses for the accelerations at sample times
!! (exact at the step ends, where g was evaluated).
!!
!!   RK4       classical Runge-Kutta, fixed step, Hermite dense output
!!   ABM4      Adams-Bashforth-Moulton 4 PECE, fixed step, started by RK4
!!   ADAMS     variable-step variable-order (1-12) Adams PECE with error
!!             control, Shampine & Gordon's divided-difference formulation
!!   DOPRI5    Dormand-Prince 5(4) with error control and 4th-order dense output
!!   ROS2      linearly implicit Rosenbrock method of order 2 with a 3rd-order
!!             error estimate (Shampine & Reichelt's L-stable pair), Jacobian by
!!             finite differences, for stiff decks
!!   ROS34PW2  Rosenbrock-W method of order 3 (embedded 2), L-stable and
!!             stiffly accurate (Rang & Angermann 2005): order 3 with any
!!             approximation of the Jacobian, so the Jacobian (structured,
!!             from the system's tangent, or by differences) and its
!!             factorization are kept over many steps; dense output of
!!             order 3 from the stages
!!
!! The procedures of the methods are in submodules: hn_integrators_explicit
!! (RK4, ABM4, DOPRI5), hn_integrators_adams, hn_integrators_rosenbrock.
module hn_integrators
    use hn_kinds, only: wp, zero, one, two, half, msglen
    use hn_status, only: stat_ok, stat_bad_input, stat_step_failed, stat_singular
    use hn_ode, only: ode_system_t
    use hn_iteration_matrix, only: iteration_matrix_t
    implicit none
    private

    public :: integrator_t, new_integrator, spectral_radius, integrator_names, interpolate_hermite
    public :: rk4_t, abm4_t, adams_t, dopri5_t, ros2_t, rosw_t
    public :: jacobian_steps_default, factor_band_default, factor_band_max

    !> Deck names of the integrators (the CONTROL card and new_integrator).
    character(len=8), parameter :: integrator_names(6) = [character(len=8) :: 'RK4', 'ABM4', 'ADAMS', 'DOPRI5', &
                                                          'ROS2', 'ROS34PW2']

    !> Relative gap below which a time counts as reached (output and stop
    !! times compared with the integrator's time).
    real(wp), parameter :: time_reached = 1.0e-12_wp
    !> Smallest error norm used in step-size formulas (an exact step would
    !! otherwise ask for an infinite step).
    real(wp), parameter :: err_floor = 1.0e-10_wp
    !> A step is stretched to end on tstop when it would stop within this
    !! fraction of a step before it.
    real(wp), parameter :: stretch = 1.01_wp
    !> h |lambda| on the negative real axis beyond which the fixed-step
    !! methods are unstable: RK4 about 2.78; ABM4 PECE about 1.3, taken as 1.2.
    real(wp), parameter :: rk4_stability = 2.78_wp, abm4_stability = 1.2_wp
    !> Step-size change limits of the error-controlled methods per step.
    real(wp), parameter :: fac_min = 0.2_wp, fac_max = 5.0_wp
    !> A step at least this fraction of the planned one was not shortened to
    !! land on tstop (a shortened step does not shrink the next).
    real(wp), parameter :: unclipped = 0.999_wp
    !> ROS34PW2's reuse of its Jacobian and factorization (SOLVER card F3,
    !! F4): one Jacobian serves at most this many accepted steps (and a
    !! rejected step with an aged one forms a new one) ... On the shipped
    !! decks, whose one-way elements change the stiffness as they switch, 3-6
    !! steps cost 9 % less integration work than 20 (fewer rejected and
    !! shorter steps; docs/performance.md).
    integer, parameter :: jacobian_steps_default = 5
    !> ... and the factorization of I - h0 gamma J serves every step h with
    !! h0/band <= h <= h0 band (1: refactor on every change of h, and a
    !! proposed growth of up to 1.2 times is not taken). A band saves
    !! factorizations but gives up L-stability (|R(-inf)| up to 0.40 at 1.25)
    !! and saved no work on the shipped decks.
    real(wp), parameter :: factor_band_default = 1.0_wp
    !> Largest band: with the factorization of h0 a step h solves with the
    !! Jacobian (h0/h) J, and the method's stability function stays bounded
    !! by 1 on the left half-plane for h0/h >= 0.62 (h <= 1.6 h0) only.
    real(wp), parameter :: factor_band_max = 1.5_wp

    !> Common state and settings of an integrator.
    type, abstract :: integrator_t
        private
        real(wp) :: h = 1.0e-4_wp       !! fixed step, or first trial step [s]
        real(wp) :: rtol = 1.0e-6_wp    !! relative tolerance (error-controlled methods)
        real(wp) :: atol = 1.0e-8_wp    !! absolute tolerance
        real(wp) :: hmin = 1.0e-12_wp   !! smallest step before giving up [s]
        real(wp) :: hmax = huge(1.0_wp) !! largest step [s]
        real(wp) :: limit = huge(1.0_wp) !! h |lambda| stability limit (huge: error-controlled)
        real(wp) :: t = zero            !! current time
        real(wp) :: told = zero         !! start of the last step
        real(wp), allocatable :: y(:), f(:), yold(:), fold(:)
        integer :: nsteps = 0           !! accepted steps
        integer :: nreject = 0          !! rejected steps
        integer :: njac = 0             !! Jacobians formed (linearly implicit methods)
        integer :: nfact = 0            !! factorizations of the iteration matrix
        integer :: jac_steps = jacobian_steps_default  !! accepted steps one Jacobian serves at most (ROS34PW2)
        real(wp) :: band = factor_band_default          !! step-size band of one factorization (ROS34PW2)
    contains
        procedure :: init => integrator_init
        procedure :: set_step => integrator_set_step
        procedure :: set_tolerances => integrator_set_tolerances
        procedure :: set_max_step => integrator_set_max_step
        procedure :: set_jacobian_reuse => integrator_set_jacobian_reuse
        procedure :: restart => integrator_restart
        procedure :: reset_history => integrator_reset_history
        procedure :: interpolate => interpolate_hermite
        procedure :: advance => integrator_advance
        procedure :: stability_limit => integrator_stability_limit
        procedure :: current_time => integrator_current_time
        procedure :: current_state => integrator_current_state
        procedure :: previous_time => integrator_previous_time
        procedure :: previous_state => integrator_previous_state
        procedure :: steps => integrator_steps
        procedure :: rejected => integrator_rejected
        procedure :: jacobians => integrator_jacobians
        procedure :: factorizations => integrator_factorizations
        procedure(step_interface), deferred :: step
    end type integrator_t

    abstract interface
        !> One accepted step from (t, y), not passing tstop.
        subroutine step_interface(me, sys, tstop, stat, errmsg)
            import :: integrator_t, ode_system_t, wp, msglen
            class(integrator_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, or why no step could be taken (hn_status)
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine step_interface
    end interface

    !> Classical fourth-order Runge-Kutta, fixed step.
    type, extends(integrator_t) :: rk4_t
    contains
        procedure :: step => rk4_step
    end type rk4_t

    !> Adams-Bashforth-Moulton 4 in PECE mode, fixed step, started by RK4.
    type, extends(integrator_t) :: abm4_t
        private
        real(wp), allocatable :: fh(:, :)   !! f at t-h, t-2h, t-3h
        integer :: nhist = 0
        real(wp) :: hhist = zero           !! step of the history
    contains
        procedure :: step => abm4_step
        procedure :: reset_history => abm4_reset_history
    end type abm4_t

    !> Dormand-Prince 5(4), error control, dense output.
    type, extends(integrator_t) :: dopri5_t
        private
        real(wp) :: hnext = zero
        real(wp), allocatable :: rcont(:, :)  !! (n, 5) dense-output coefficients of the last step
    contains
        procedure :: step => dopri5_step
        procedure :: interpolate => dopri5_interpolate
        procedure :: reset_history => dopri5_reset_history
    end type dopri5_t

    !> Variable-step, variable-order Adams PECE (Shampine & Gordon).
    type, extends(integrator_t) :: adams_t
        private
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
        private
        real(wp) :: hnext = zero
        integer :: jac_age = -1          !! accepted steps since the Jacobian was formed (-1: none)
        integer :: jac_age_max = 5
        type(iteration_matrix_t) :: w    !! Jacobian (dense, differences) and factorization of I - h d J
        real(wp), allocatable :: tdot(:) !! dg/dt by a forward difference
    contains
        procedure :: step => ros2_step
        procedure :: reset_history => ros2_reset_history
    end type ros2_t

    !> Rosenbrock-W ROS34PW2: the Jacobian is formed at the start, after a
    !! rejected step when it has aged, and every `jac_steps` accepted steps;
    !! the factorization when the Jacobian is new or h leaves the band of
    !! the factored step (`band`; 1: whenever h changes).
    type, extends(integrator_t) :: rosw_t
        private
        real(wp) :: hnext = zero
        integer :: jac_age = -1
        type(iteration_matrix_t) :: w
        real(wp), allocatable :: u(:, :)  !! (n, 4) stages of the last step (dense output)
        real(wp) :: hacc = zero           !! the last accepted step (Gustafsson's controller; 0: none yet)
        real(wp) :: erracc = zero         !! its error norm (at least 1e-2)
    contains
        procedure :: step => rosw_step
        procedure :: interpolate => rosw_interpolate
        procedure :: reset_history => rosw_reset_history
    end type rosw_t

    interface
        !> Step size limited so that the step ends exactly on tstop when it
        !! would otherwise pass it or stop just short of it.
        pure module function clip_step(t, h, tstop) result(hc)
            real(wp), intent(in) :: t       !! current time [s]
            real(wp), intent(in) :: h       !! planned step [s]
            real(wp), intent(in) :: tstop   !! time the step may not pass [s]
            real(wp) :: hc
        end function clip_step
        !> Accept a step: old point <- current, current <- (tnew, ynew, fnew).
        module subroutine accept(me, tnew, ynew, fnew)
            class(integrator_t), intent(inout) :: me
            real(wp), intent(in) :: tnew      !! time at the end of the step [s]
            real(wp), intent(in) :: ynew(:)   !! state at tnew
            real(wp), intent(in) :: fnew(:)   !! g(tnew, ynew)
        end subroutine accept
        !> Weighted RMS norm of e with weights atol + rtol max(|y0|, |y1|).
        pure module function err_norm(me, e, y0, y1) result(r)
            class(integrator_t), intent(in) :: me
            real(wp), intent(in) :: e(:)    !! local error estimate
            real(wp), intent(in) :: y0(:)   !! state at the start of the step
            real(wp), intent(in) :: y1(:)   !! state at its end
            real(wp) :: r
        end function err_norm
        !> Interpolation at or beyond the end of the last step (or with no
        !! step yet): y and f of the current point; .false. otherwise.
        module function at_current_point(me, tout, yout, dydt) result(done)
            class(integrator_t), intent(in) :: me
            real(wp), intent(in) :: tout                 !! time asked for [s]
            real(wp), intent(out) :: yout(:)             !! the current y when done
            real(wp), intent(out), optional :: dydt(:)   !! the current f when done
            logical :: done
        end function at_current_point
        !> The message of a step size below hmin.
        module subroutine step_too_small(t, hmin, stat, errmsg)
            real(wp), intent(in) :: t                      !! time of the failure [s]
            real(wp), intent(in) :: hmin                   !! the smallest step allowed [s]
            integer, intent(out) :: stat                   !! stat_step_failed
            character(len=msglen), intent(out) :: errmsg   !! the message (the run adds the remedy for its method)
        end subroutine step_too_small
        module subroutine rk4_step(me, sys, tstop, stat, errmsg)
            class(rk4_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, or the system's failure
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine rk4_step
        module subroutine abm4_step(me, sys, tstop, stat, errmsg)
            class(abm4_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, or the system's failure
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine abm4_step
        module subroutine abm4_reset_history(me)
            class(abm4_t), intent(inout) :: me
        end subroutine abm4_reset_history
        module subroutine dopri5_step(me, sys, tstop, stat, errmsg)
            class(dopri5_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, stat_step_failed (h < hmin), or the system's
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine dopri5_step
        module subroutine dopri5_interpolate(me, tout, yout, dydt)
            class(dopri5_t), intent(in) :: me
            real(wp), intent(in) :: tout                 !! time within the last step [s]
            real(wp), intent(out) :: yout(:)             !! y(tout)
            real(wp), intent(out), optional :: dydt(:)   !! y'(tout) of the interpolant
        end subroutine dopri5_interpolate
        module subroutine dopri5_reset_history(me)
            class(dopri5_t), intent(inout) :: me
        end subroutine dopri5_reset_history
        module subroutine adams_step(me, sys, tstop, stat, errmsg)
            class(adams_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, stat_step_failed (h < hmin), or the system's
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine adams_step
        module subroutine adams_interpolate(me, tout, yout, dydt)
            class(adams_t), intent(in) :: me
            real(wp), intent(in) :: tout                 !! time within the last step [s]
            real(wp), intent(out) :: yout(:)             !! y(tout)
            real(wp), intent(out), optional :: dydt(:)   !! y'(tout) of the interpolant
        end subroutine adams_interpolate
        module subroutine adams_reset_history(me)
            class(adams_t), intent(inout) :: me
        end subroutine adams_reset_history
        module subroutine ros2_step(me, sys, tstop, stat, errmsg)
            class(ros2_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, stat_step_failed, stat_singular, or the system's
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine ros2_step
        module subroutine ros2_reset_history(me)
            class(ros2_t), intent(inout) :: me
        end subroutine ros2_reset_history
        module subroutine rosw_step(me, sys, tstop, stat, errmsg)
            class(rosw_t), intent(inout) :: me
            class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
            real(wp), intent(in) :: tstop                  !! time the step may not pass [s]
            integer, intent(out) :: stat                   !! stat_ok, stat_step_failed, stat_singular, or the system's
            character(len=msglen), intent(out) :: errmsg   !! the reason, with the time ('' when stat_ok)
        end subroutine rosw_step
        module subroutine rosw_interpolate(me, tout, yout, dydt)
            class(rosw_t), intent(in) :: me
            real(wp), intent(in) :: tout                 !! time within the last step [s]
            real(wp), intent(out) :: yout(:)             !! y(tout)
            real(wp), intent(out), optional :: dydt(:)   !! y'(tout) of the interpolant
        end subroutine rosw_interpolate
        module subroutine rosw_reset_history(me)
            class(rosw_t), intent(inout) :: me
        end subroutine rosw_reset_history
    end interface

contains

    !> A new integrator by its deck name (one of integrator_names);
    !! stat = stat_bad_input for an unknown name.
    subroutine new_integrator(name, integ, stat)
        character(len=*), intent(in) :: name                  !! deck name
        class(integrator_t), allocatable, intent(out) :: integ  !! the integrator, settings at their defaults
        integer, intent(out) :: stat                          !! stat_ok or stat_bad_input
        stat = stat_ok
        select case (name)
        case ('RK4')
            allocate (rk4_t :: integ)
            integ%limit = rk4_stability
        case ('ABM4')
            allocate (abm4_t :: integ)
            integ%limit = abm4_stability
        case ('ADAMS'); allocate (adams_t :: integ)
        case ('DOPRI5'); allocate (dopri5_t :: integ)
        case ('ROS2'); allocate (ros2_t :: integ)
        case ('ROS34PW2'); allocate (rosw_t :: integ)
        case default
            stat = stat_bad_input
            allocate (rk4_t :: integ)
        end select
    end subroutine new_integrator

    !> The fixed step, or the first trial step of the error-controlled methods.
    subroutine integrator_set_step(me, h)
        class(integrator_t), intent(inout) :: me
        real(wp), intent(in) :: h      !! [s]
        me%h = h
    end subroutine integrator_set_step

    !> The largest step of the error-controlled methods (a fixed step when
    !! equal to the first step and the tolerances are loose).
    subroutine integrator_set_max_step(me, hmax)
        class(integrator_t), intent(inout) :: me
        real(wp), intent(in) :: hmax   !! [s]
        me%hmax = hmax
    end subroutine integrator_set_max_step

    !> How long ROS34PW2 keeps its Jacobian and its factorization (other
    !! methods ignore it): a new Jacobian after `steps` accepted steps (and
    !! after a rejected step with an aged one), a new factorization of
    !! I - h gamma J when the step leaves [h0/band, h0 band] of the factored
    !! step h0. steps = 20, band = 1 is the rule of earlier versions
    !! (results equal to theirs bit for bit).
    subroutine integrator_set_jacobian_reuse(me, steps, band)
        class(integrator_t), intent(inout) :: me
        integer, intent(in) :: steps     !! accepted steps per Jacobian (>= 1)
        real(wp), intent(in) :: band     !! step-size factor of one factorization (1 to factor_band_max)
        me%jac_steps = max(1, steps)
        me%band = min(max(one, band), factor_band_max)
    end subroutine integrator_set_jacobian_reuse

    !> Relative and absolute error tolerances (error-controlled methods).
    subroutine integrator_set_tolerances(me, rtol, atol)
        class(integrator_t), intent(inout) :: me
        real(wp), intent(in) :: rtol   !! relative tolerance
        real(wp), intent(in) :: atol   !! absolute tolerance
        me%rtol = rtol
        me%atol = atol
    end subroutine integrator_set_tolerances

    !> Start at (t0, y0).
    subroutine integrator_init(me, sys, t0, y0, stat, errmsg)
        class(integrator_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys      !! the system
        real(wp), intent(in) :: t0                     !! initial time
        real(wp), intent(in) :: y0(:)                  !! initial state
        integer, intent(out) :: stat                   !! stat_ok or the system's failure
        character(len=msglen), intent(out) :: errmsg   !! the system's message ('' when stat_ok)
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
        class(ode_system_t), intent(inout) :: sys      !! the system
        integer, intent(out) :: stat                   !! stat_ok or the system's failure
        character(len=msglen), intent(out) :: errmsg   !! the system's message ('' when stat_ok)
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
        r = me%limit
    end function integrator_stability_limit

    !> Current time.
    pure real(wp) function integrator_current_time(me) result(t)
        class(integrator_t), intent(in) :: me
        t = me%t
    end function integrator_current_time

    !> Current state.
    pure function integrator_current_state(me) result(y)
        class(integrator_t), intent(in) :: me
        real(wp), allocatable :: y(:)
        y = me%y
    end function integrator_current_state

    !> Start of the last step.
    pure real(wp) function integrator_previous_time(me) result(t)
        class(integrator_t), intent(in) :: me
        t = me%told
    end function integrator_previous_time

    !> State at the start of the last step.
    pure function integrator_previous_state(me) result(y)
        class(integrator_t), intent(in) :: me
        real(wp), allocatable :: y(:)
        y = me%yold
    end function integrator_previous_state

    !> Accepted steps so far.
    pure integer function integrator_steps(me) result(k)
        class(integrator_t), intent(in) :: me
        k = me%nsteps
    end function integrator_steps

    !> Rejected steps so far.
    pure integer function integrator_rejected(me) result(k)
        class(integrator_t), intent(in) :: me
        k = me%nreject
    end function integrator_rejected

    !> Jacobians formed so far (0 for the explicit methods).
    pure integer function integrator_jacobians(me) result(k)
        class(integrator_t), intent(in) :: me
        k = me%njac
    end function integrator_jacobians

    !> Factorizations of the iteration matrix so far (0 for the explicit methods).
    pure integer function integrator_factorizations(me) result(k)
        class(integrator_t), intent(in) :: me
        k = me%nfact
    end function integrator_factorizations

    !> Step until t >= tout (never past tstop) and interpolate y at tout.
    subroutine integrator_advance(me, sys, tout, yout, tstop, stat, errmsg)
        class(integrator_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys      !! the system
        real(wp), intent(in) :: tout                   !! output time
        real(wp), intent(out) :: yout(:)               !! y at tout
        real(wp), intent(in) :: tstop                  !! time no step may pass
        integer, intent(out) :: stat                   !! stat_ok or why a step failed
        character(len=msglen), intent(out) :: errmsg   !! why a step failed ('' when stat_ok)
        stat = stat_ok; errmsg = ''
        do while (me%t < tout - time_reached*max(one, abs(tout)))
            call me%step(sys, max(tstop, tout), stat, errmsg)
            if (stat /= stat_ok) return
        end do
        call me%interpolate(tout, yout)
    end subroutine integrator_advance

    !> Cubic Hermite interpolation between (told, yold, fold) and (t, y, f),
    !! and its derivative: the dense output of RK4 and ABM4, and for every
    !! method the interpolant of the last step's end points.
    subroutine interpolate_hermite(me, tout, yout, dydt)
        class(integrator_t), intent(in) :: me       !! the integrator after a step
        real(wp), intent(in) :: tout            !! time in the last step
        real(wp), intent(out) :: yout(:)        !! y(tout)
        real(wp), intent(out), optional :: dydt(:)  !! y'(tout) of the interpolant
        real(wp) :: h, s, h00, h10, h01, h11
        if (at_current_point(me, tout, yout, dydt)) return
        h = me%t - me%told
        s = (tout - me%told)/h
        h00 = (one + two*s)*(one - s)**2
        h10 = s*(one - s)**2
        h01 = s**2*(3.0_wp - two*s)
        h11 = s**2*(s - one)
        yout = h00*me%yold + h10*h*me%fold + h01*me%y + h11*h*me%f
        if (present(dydt)) then
            h00 = 6.0_wp*s*(s - one)
            h10 = (one - s)*(one - 3.0_wp*s)
            h11 = s*(3.0_wp*s - two)
            dydt = (h00*me%yold - h00*me%y)/h + h10*me%fold + h11*me%f
        end if
    end subroutine interpolate_hermite

    !> Estimate of the spectral radius of dg/dy at (t, y) by power iteration
    !! on finite-difference Jacobian-vector products; `lead` is the
    !! component with the largest entry of the dominant eigenvector.
    subroutine spectral_radius(sys, t, y, rho, lead, stat, errmsg)
        class(ode_system_t), intent(inout) :: sys      !! the system
        real(wp), intent(in) :: t                      !! time of the point [s]
        real(wp), intent(in) :: y(:)                   !! state at the point
        real(wp), intent(out) :: rho                   !! spectral radius estimate [1/s]
        integer, intent(out) :: lead                   !! component leading the dominant mode
        integer, intent(out) :: stat                   !! stat_ok or the system's failure
        character(len=msglen), intent(out) :: errmsg   !! the system's message ('' when stat_ok)
        integer, parameter :: power_iterations = 40
        real(wp) :: f0(size(y)), f1(size(y)), v(size(y)), u(size(y)), d, nv
        integer :: it, n, j
        n = size(y) - sys%nquad
        call sys%rhs(t, y, f0, stat, errmsg)
        if (stat /= stat_ok) return
        do j = 1, size(y)
            v(j) = one + 0.1_wp*sin(real(7*j, wp))
        end do
        v(n + 1:) = zero
        v = v/norm2(v)
        rho = zero
        lead = 1
        do it = 1, power_iterations
            d = sqrt(epsilon(one))*max(one, norm2(y(1:n)))
            call sys%rhs(t, y + d*v, f1, stat, errmsg)
            if (stat /= stat_ok) return
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
