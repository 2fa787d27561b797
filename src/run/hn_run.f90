!> Running a case as a run object: `start` (listing header, posture holding,
!! integrator, result file), then `advance_to` each output time (the
!! integrator's own steps, ending on the breakpoints of the input tables and
!! on the switching points of the one-way elements when asked, with the
!! checks that stop a diverging run), `output` there (channels from the
!! dense output, samples, listing rows, dumps, peaks), and `finish`
!! (injury assessment, listing tables, energy balance, file status).
!! `execute` runs all of it. The main program, the sweeps and the
!! benchmarks use this one object.
module hn_run
    use hn_kinds, only: wp, zero, one, msglen, i8, deg
    use hn_status, only: stat_ok, stat_not_finite, stat_energy_lost
    use hn_case, only: case_t
    use hn_dynamics, only: model_ode_t, model_ode_init, coordinates_to_state, state_size, energy_terms, &
                           energy_t, dynamics_outputs, inertia_forces_free, state_to_coordinates, &
                           set_element_states, energy_integrals
    use hn_forces, only: switch_count, switching_functions
    use hn_integrators, only: integrator_t, new_integrator, spectral_radius, interpolate_hermite
    use hn_channels, only: channel_set_t, channels_define, channels_compute, channels_start, channel_index
    use hn_results, only: results_t
    use hn_listing, only: listing_t
    use hn_dump, only: dump_record
    use hn_breakpoints, only: case_breakpoints
    use hn_model, only: hold_breakpoints, hold_pass, neutral_coordinates, control_times, control_pass
    use hn_kinematics, only: body_kinematics
    use hn_tree, only: dof_label
    use hn_prestrain, only: prestrain_t, settle_prestrain
    use hn_deck_reader, only: upper
    use hn_assessment, only: assessment_t, assess, criteria_input_t, criteria_input_from, criteria_channels, &
                             ncriteria_columns
    use hn_signals, only: signal_received
    use hn_progress, only: progress_t, limit_diagnosis, stop_remedy
    use hn_history, only: history_t
    use hn_version, only: code_version
    implicit none
    private

    public :: run_state_t, run_result_t

    integer, parameter, public :: exit_ok = 0, exit_usage = 1, exit_deck = 2, exit_diverged = 3, &
                                  exit_output = 4, exit_interrupted = 5, &
                                  exit_members_failed = 6

    !> |switching function| below which a one-way element counts as on its
    !! switch: a coordinate resting on its neutral value (roundoff noise)
    !! must not switch at every step.
    real(wp), parameter :: switch_deadband = 1.0e-8_wp
    !> Output times closer than this fraction of the sampling interval are
    !! the same time (a sample that is also a print time is one output).
    real(wp), parameter :: time_match = 1.0e-9_wp
    !> A complete run whose largest energy-balance residual exceeds this
    !! fraction of the energy flows is reported as inaccurate.
    real(wp), parameter :: energy_warn_fraction = 0.01_wp
    !> A residual beyond this fraction of the energy flows (plus the floor
    !! below) means the solution grows without a physical cause: the run stops.
    real(wp), parameter :: energy_fail_fraction = 0.5_wp
    real(wp), parameter :: energy_fail_floor = 1.0e-3_wp   !! [J] so that a run at rest is not stopped by roundoff
    !> Event location: steps shorter than this are not searched [s], the
    !! switching time is located to this width [s] in at most this many
    !! regula-falsi iterations.
    real(wp), parameter :: event_min_step = 1.0e-9_wp, event_width = 1.0e-10_wp
    integer, parameter :: event_max_iter = 40
    !> The stability diagnosis proposes this fraction of the stable step.
    real(wp), parameter :: stable_step_margin = 0.8_wp

    !> What happened in a run.
    type :: run_result_t
        integer :: exit_code = exit_ok
        character(len=12) :: status = 'complete'
        character(len=msglen) :: message = ''
        character(len=msglen) :: warning = ''   !! a complete run whose results are doubtful
        character(len=msglen) :: file_note = '' !! what happened to result files (removed, created, kept in)
        real(wp) :: t_reached = zero
        integer :: nevals = 0            !! dynamics evaluations of the integrator
        integer :: nevals_output = 0     !! evaluations at output times
        integer :: nsteps = 0, nreject = 0, nevents = 0, njac = 0
        integer :: nfact = 0             !! factorizations of the iteration matrix (implicit methods)
        real(wp) :: wall = zero          !! wall-clock time of the run loop [s]
        real(wp) :: energy_residual = zero   !! largest |energy balance residual| [J]
        real(wp) :: energy_scale = zero      !! largest sum of energy-term magnitudes [J]
        integer :: nrows = 0                             !! rows of the listing's time histories
        !> peaks of the families' run monitors in family order (the limits':
        !! excess beyond each joint's range, ROM cards) [rad]
        real(wp), allocatable :: range_peak(:)
        real(wp), allocatable :: samples_t(:), samples(:, :)  !! (optional) every channel at every sample
        real(wp), allocatable :: samples_head_s(:, :, :)      !! (optional) head rotation matrix (head axes -> R) at every sample
        type(assessment_t) :: criteria                   !! injury criteria of the run
    end type run_result_t

    !> The peaks of one family's run monitor and when they occurred.
    type :: monitor_peaks_t
        real(wp), allocatable :: peak(:), time(:)   !! (monitor_count) largest excess [family's units], when [s]
    end type monitor_peaks_t

    !> Highest and lowest value of every channel and when they occurred.
    type :: peaks_t
        real(wp), allocatable :: vmax(:), vmin(:), tmax(:), tmin(:)
    end type peaks_t

    !> A run in progress.
    type :: run_state_t
        private
        type(case_t) :: cs                          !! the case (posture-holding forces filled in at start)
        type(model_ode_t) :: sys                    !! the model as an ODE system
        class(integrator_t), allocatable :: integ
        type(channel_set_t) :: ch
        type(results_t) :: out
        type(listing_t) :: lst
        type(energy_t) :: en0                       !! energy terms at the start
        type(run_result_t) :: res
        type(peaks_t) :: peaks
        type(monitor_peaks_t), allocatable :: mon(:)  !! (families) peaks of each family's run monitor
        integer :: icol(size(criteria_channels)) = 0  !! the criteria_channels' indices in the channel set
        type(history_t) :: rows                     !! listing rows (t, every channel), memory bounded
        type(history_t) :: crit                     !! assessment inputs at every sample, memory bounded
        type(progress_t) :: prog                    !! progress display and run limits
        real(wp), allocatable :: tb(:)              !! breakpoints of the input tables
        real(wp), allocatable :: tc(:)              !! sample times of the model's controllers (FEEDBACK cards)
        real(wp), allocatable :: sw_old(:)          !! switching functions after the last accepted step
        real(wp), allocatable :: ygood(:)           !! last accepted state ...
        real(wp) :: tgood = zero                    !! ... and its time
        real(wp) :: tol = zero                      !! time_match times the sampling interval [s]
        real(wp) :: tout = zero                     !! the output time being approached [s]
        integer :: ib = 1                           !! next breakpoint
        integer :: ic = 1                           !! next controller sample time
        integer :: nsw = 0                          !! number of switching functions
        integer :: ks = 0, kp = 0, kd = 1           !! samples and listing rows written, next dump
        integer :: nev_out = 0                      !! evaluations made for outputs
        logical :: pending_restart = .false.        !! restart the integrator before its next step
        logical :: pending_control = .false.        !! the controllers sample before the next step
        logical :: keep = .false.                   !! keep every sample in the result (benchmarks, sweeps)
        logical :: rated = .false.                  !! only the named channels (a calibration member): no
                                                    !! listing rows, histories, peaks or injury criteria
        logical :: running = .false.
        integer(i8) :: clock0 = 0_i8
    contains
        procedure :: execute => run_execute
        procedure :: start => run_start
        procedure :: advance_to => run_advance_to
        procedure :: output => run_output
        procedure :: locate_events => run_locate_events
        procedure :: finish => run_finish
        procedure :: next_output_time => run_next_output_time
        procedure :: is_running => run_is_running
        procedure :: time_reached => run_time_reached
        procedure, private :: hold_posture, settle, init_outputs, check_state, diagnosis, fail, track_peaks
        procedure, private :: record_sample, control_sample
    end type run_state_t

contains

    !> Run the case from start to end (or to the failure that stops it),
    !! writing the listing on unit lu and results to h5name ('' for none).
    !! With keep_samples, every channel at every sample is returned in res.
    subroutine run_execute(me, cs, lu, h5name, res, keep_samples, only)
        class(run_state_t), intent(inout) :: me
        type(case_t), intent(in) :: cs                !! the case to run
        integer, intent(in) :: lu                     !! listing unit
        character(len=*), intent(in) :: h5name        !! result file name ('' for none)
        type(run_result_t), intent(out) :: res        !! what happened
        logical, intent(in), optional :: keep_samples !! keep every channel at every sample in res
        character(len=*), intent(in), optional :: only(:) !! compute only these channels (no listing tables, criteria)
        call me%start(cs, lu, h5name, keep_samples, only)
        do while (me%is_running())
            call me%advance_to(me%next_output_time())
            if (me%is_running()) call me%output()
        end do
        call me%finish(res)
    end subroutine run_execute

    !> Listing header and model summary, initial state, posture holding,
    !! integrator, result file and output schedule.
    subroutine run_start(me, cs, lu, h5name, keep_samples, only)
        class(run_state_t), intent(inout) :: me
        type(case_t), intent(in) :: cs                !! the case to run
        integer, intent(in) :: lu                     !! listing unit
        character(len=*), intent(in) :: h5name        !! result file name ('' for none)
        logical, intent(in), optional :: keep_samples !! keep every channel at every sample
        character(len=*), intent(in), optional :: only(:) !! compute only these channels (no listing tables, criteria)
        real(wp), allocatable :: y(:)
        integer :: stat
        character(len=msglen) :: msg
        integer(i8) :: rate
        me%cs = cs
        me%keep = .false.
        if (present(keep_samples)) me%keep = keep_samples
        me%rated = present(only)
        if (allocated(me%cs%subtitles)) then
            call me%lst%start(lu, me%cs%model%title, code_version, me%cs%subtitles)
        else
            call me%lst%start(lu, me%cs%model%title, code_version)
        end if
        call me%lst%echo_deck(me%cs%deck)
        call channels_define(me%cs, me%ch, only)
        call model_ode_init(me%sys, me%cs%model)
        allocate (y(state_size(me%sys)))
        call coordinates_to_state(me%sys%ws, me%cs%x0, me%cs%xd0, y)
        me%res%warning = ''
        if (me%cs%hold_posture) then
            call me%hold_posture(y, stat, msg)
            if (stat /= stat_ok) then
                call me%fail(exit_diverged, 'posture holding: '//trim(msg))
                return
            end if
        else if (me%cs%hold_prestrain) then
            call me%settle(stat, msg)
            if (stat /= stat_ok) then
                call me%fail(exit_deck, trim(me%cs%hold_where)//' (HOLD PRESTRAIN): '//trim(msg))
                return
            end if
        end if
        call me%lst%model_summary(me%cs)
        if (len_trim(me%res%warning) > 0) call me%lst%message(me%res%warning)
        call new_integrator(me%cs%integrator, me%integ, stat)
        if (stat /= stat_ok) then
            call me%fail(exit_deck, 'unknown integrator "'//trim(me%cs%integrator)//'"')
            return
        end if
        call me%integ%set_step(me%cs%h)
        call me%integ%set_tolerances(me%cs%rtol, me%cs%atol)
        call me%integ%set_jacobian_reuse(me%cs%jac_steps, me%cs%jac_band)
        call me%integ%init(me%sys, me%cs%t_start, y, stat, msg)
        if (stat /= stat_ok) then
            call me%fail(exit_diverged, trim(msg))
            return
        end if
        me%en0 = energy_terms(me%sys%model, me%sys%ws, energy_integrals(y))
        me%ch%e0 = me%en0%total
        call channels_start(me%cs, me%sys%ws, me%ch)
        if (len_trim(h5name) > 0) then
            call me%out%open(me%cs, me%ch, trim(h5name), code_version, stat, msg, me%res%file_note)
            if (stat /= stat_ok) then
                call me%fail(exit_output, trim(msg))
                return
            end if
        end if
        call me%init_outputs()
        me%tgood = me%cs%t_start
        me%ygood = y
        me%running = .true.
        call system_clock(me%clock0, rate)
        call me%prog%start(me%cs%t_start, me%cs%t_end, me%cs%progress, me%cs%wall_limit, me%cs%step_limit)
    end subroutine run_start

    !> Constant generalized forces that hold the start posture: q_hold =
    !! -a_FF xddot_F at the initial state (then xddot_F = 0 there).
    subroutine hold_posture(me, y, stat, msg)
        class(run_state_t), intent(inout) :: me
        real(wp), intent(in) :: y(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        real(wp) :: dydt(size(y))
        integer :: nf
        nf = me%sys%ws%nfree
        call me%sys%rhs(me%cs%t_start, y, dydt, stat, msg)
        if (stat /= stat_ok) return
        associate (ws => me%sys%ws)
            me%sys%model%q_hold(ws%ifree) = -inertia_forces_free(me%sys%model, ws, dydt(nf + 1:2*nf))
        end associate
        me%cs%model%q_hold = me%sys%model%q_hold
    end subroutine hold_posture

    !> HOLD PRESTRAIN: the model pre-strained so that it stands in its
    !! start posture (hn_prestrain), the system rebuilt on it, a note for
    !! the listing.
    subroutine settle(me, stat, msg)
        class(run_state_t), intent(inout) :: me
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        type(prestrain_t) :: ps
        real(wp), allocatable :: xr(:)
        character(len=:), allocatable :: w
        integer :: f
        call settle_prestrain(me%cs%model, me%cs%t_start, me%cs%x0, me%cs%xd0, ps, stat, msg)
        if (stat /= stat_ok) return
        call model_ode_init(me%sys, me%cs%model)
        write (me%cs%hold_note, '(a,es10.3,a,i0,a)') 'LARGEST LOAD ', ps%load, ' N OR N M, SETTLED IN ', ps%iterations, &
            ' NEWTON ITERATIONS'
        if (ps%largest > 0) write (me%cs%hold_note, '(a,f8.3,3a)') trim(me%cs%hold_note)//'; LARGEST ROTATION SHIFT ', &
            ps%dx(ps%largest)/deg, ' DEG AT ', trim(upper(dof_label(me%cs%model%tree, ps%largest)))
        ! a warning of a family on the settled start (the limits': a neutral out of its joint's range)
        xr = neutral_coordinates(me%cs%model)
        do f = 1, size(me%cs%model%family)
            w = me%cs%model%family(f)%f%neutral_warning(xr, ps%dx)
            if (len(w) == 0) cycle
            me%res%warning = w
            exit
        end do
    end subroutine settle

    !> Output schedule, listing rows, sample store, peaks, breakpoints and
    !! switching functions.
    subroutine init_outputs(me)
        class(run_state_t), intent(inout) :: me
        integer :: nsample, k
        associate (cs => me%cs)
            nsample = nint((cs%t_end - cs%t_start)/cs%sample_dt) + 2
            call me%rows%init(1 + me%ch%n)
            if (me%keep) allocate (me%res%samples_t(nsample), me%res%samples(me%ch%n, nsample), &
                                   me%res%samples_head_s(3, 3, nsample))
            call me%crit%init(ncriteria_columns)
            me%icol = [(channel_index(me%ch, criteria_channels(k)), k = 1, size(criteria_channels))]
            allocate (me%peaks%vmax(me%ch%n), me%peaks%vmin(me%ch%n), me%peaks%tmax(me%ch%n), &
                      me%peaks%tmin(me%ch%n))
            me%peaks%vmax = -huge(one); me%peaks%vmin = huge(one)
            me%peaks%tmax = cs%t_start; me%peaks%tmin = cs%t_start
            me%tb = [real(wp) ::]
            if (cs%events /= 'NONE') me%tb = case_breakpoints(cs)
            me%nsw = 0
            if (cs%events == 'STATE') me%nsw = switch_count(cs%model)
            allocate (me%sw_old(me%nsw))
            if (me%nsw > 0) call switching_functions(me%sys%model, cs%t_start, me%sys%ws%kin, me%sys%ws%x, me%sw_old)
            me%ib = 1
            me%tol = time_match*max(cs%sample_dt, 1.0e-6_wp)
            ! the release of the holding forces (a step, or a ramp's ends), whatever EVENTS says
            me%tb = hold_breakpoints(cs%model, me%tb, cs%t_start, cs%t_end, me%tol)
            me%ks = 0; me%kp = 0; me%kd = 1
            ! the controllers' sample times, the first (the start) taken now
            me%tc = control_times(me%sys%model, cs%t_start, cs%t_end, me%tol)
            me%ic = 1
            me%pending_control = .false.
            if (size(me%tc) > 0) call me%control_sample(cs%t_start, me%integ%current_state())
            ! the sample changes the excitations that drive the element states: their rates jump
            if (size(me%tc) > 0 .and. me%sys%ws%nstate > 0) me%pending_restart = .true.
        end associate
        allocate (me%mon(size(me%cs%model%family)))
        do k = 1, size(me%mon)
            associate (n => me%cs%model%family(k)%f%monitor_count())
                allocate (me%mon(k)%peak(n), me%mon(k)%time(n))
            end associate
            me%mon(k)%peak = zero; me%mon(k)%time = me%cs%t_start
        end do
    end subroutine init_outputs

    !> The model's controllers sample the state y at time t (its kinematics
    !! formed in the workspace): those whose sample is due take it.
    subroutine control_sample(me, t, y)
        class(run_state_t), intent(inout) :: me
        real(wp), intent(in) :: t                     !! time reached [s]
        real(wp), intent(in) :: y(:)                  !! the state there
        integer :: nf
        nf = me%sys%ws%nfree
        associate (model => me%sys%model, ws => me%sys%ws)
            call set_element_states(model, ws, y)
            call state_to_coordinates(model, ws, t, y(1:nf), y(nf + 1:2*nf))
            call body_kinematics(model%tree, ws%x, ws%xd, ws%kin)
            call control_pass(model, t, ws%kin, me%tol)
        end associate
    end subroutine control_sample

    !> The next output time: the earliest of the next sample, listing row,
    !! dump time and the end time.
    real(wp) function run_next_output_time(me) result(tout)
        class(run_state_t), intent(in) :: me
        associate (cs => me%cs)
            tout = min(cs%t_start + me%ks*cs%sample_dt, cs%t_start + me%kp*cs%print_dt, cs%t_end)
            if (me%kd <= size(cs%dump_times)) tout = min(tout, cs%dump_times(me%kd))
        end associate
    end function run_next_output_time

    !> True while the run has not reached its end time or stopped.
    logical function run_is_running(me)
        class(run_state_t), intent(in) :: me
        run_is_running = me%running
    end function run_is_running

    !> The time the integrator's last step ended [s] (a breakpoint it
    !! landed on, or past the last output time).
    real(wp) function run_time_reached(me) result(t)
        class(run_state_t), intent(in) :: me
        t = me%integ%current_time()
    end function run_time_reached

    !> Integrate until the integrator has passed tout (its dense output then
    !! covers tout), with steps ending on the input breakpoints, events
    !! located, and the checks that stop the run on a signal, a non-finite
    !! state, a lost energy balance or an integrator failure.
    subroutine run_advance_to(me, tout)
        class(run_state_t), intent(inout) :: me
        real(wp), intent(in) :: tout                  !! the output time to reach [s]
        real(wp) :: tstop
        integer :: stat
        character(len=msglen) :: msg
        me%tout = tout
        do while (me%integ%current_time() < tout - me%tol .and. me%running)
            do while (me%ib <= size(me%tb))
                if (me%tb(me%ib) > me%integ%current_time() + me%tol) exit
                me%ib = me%ib + 1
            end do
            ! the controllers sample where the last step landed, before the
            ! next step, for the same reason as a restart (below)
            if (me%pending_control) then
                call me%control_sample(me%integ%current_time(), me%integ%current_state())
                me%pending_control = .false.
            end if
            do while (me%ic <= size(me%tc))
                if (me%tc(me%ic) > me%integ%current_time() + me%tol) exit
                me%ic = me%ic + 1
            end do
            tstop = me%cs%t_end
            if (me%ib <= size(me%tb)) tstop = min(tstop, me%tb(me%ib))
            if (me%ic <= size(me%tc)) tstop = min(tstop, me%tc(me%ic))
            ! a restart at a breakpoint or event waits until the next step, so
            ! that outputs inside the step that reached it can still be
            ! interpolated from that step
            if (me%pending_restart) then
                call hold_pass(me%sys%model, me%integ%current_time(), me%tol)
                call me%integ%restart(me%sys, stat, msg)
                me%pending_restart = .false.
                if (stat /= stat_ok) then
                    call me%fail(exit_diverged, 'run stopped at a restart: '//trim(msg)//me%diagnosis()// &
                                 stop_remedy(me%cs%integrator, me%cs%model%jacobian, msg))
                    return
                end if
            end if
            call me%integ%step(me%sys, tstop, stat, msg)
            if (signal_received() /= 0) then
                write (msg, '(a,i0,a,es12.5,a)') 'interrupted by signal ', signal_received(), ' at t = ', &
                    me%tgood, ' s'
                call me%fail(exit_interrupted, trim(msg))
                return
            end if
            if (stat == stat_ok) call me%check_state(stat, msg)
            if (stat /= stat_ok) then
                call me%fail(exit_diverged, 'run stopped: '//trim(msg)//me%diagnosis()// &
                             stop_remedy(me%cs%integrator, me%cs%model%jacobian, msg))
                return
            end if
            if (me%nsw > 0) then
                call me%locate_events(stat, msg)
                if (stat /= stat_ok) then
                    call me%fail(exit_diverged, 'run stopped: '//trim(msg))
                    return
                end if
            end if
            if (me%ib <= size(me%tb)) then
                if (abs(me%integ%current_time() - me%tb(me%ib)) <= me%tol) then
                    ! a kink or jump of an input: start the formulas afresh
                    me%pending_restart = .true.
                    me%ib = me%ib + 1
                end if
            end if
            if (me%ic <= size(me%tc)) then
                if (abs(me%integ%current_time() - me%tc(me%ic)) <= me%tol) then
                    ! a controller's sample time: the activations stay continuous;
                    ! as states of the equations their rates jump there: a restart
                    me%pending_control = .true.
                    if (me%sys%ws%nstate > 0) me%pending_restart = .true.
                    me%ic = me%ic + 1
                end if
            end if
            me%tgood = me%integ%current_time()
            me%ygood = me%integ%current_state()
            call me%prog%update(me%tgood, me%tgood - me%integ%previous_time(), me%integ%steps(), stat, msg)
            if (stat /= stat_ok) then
                call me%fail(exit_diverged, 'run stopped: '//trim(msg)// &
                             limit_diagnosis(me%sys, me%tgood, me%ygood, me%tgood - me%integ%previous_time(), &
                                             me%cs%integrator))
                return
            end if
        end do
    end subroutine run_advance_to

    !> The outputs at the current output time, from the dense output of the
    !! last step: channels, peaks, a sample, a listing row and a dump as due.
    subroutine run_output(me)
        class(run_state_t), intent(inout) :: me
        real(wp) :: t, y(size(me%ygood)), yh(size(me%ygood)), dydt(size(me%ygood))
        type(energy_t) :: en
        integer :: stat, nf
        character(len=msglen) :: msg
        associate (cs => me%cs, ws => me%sys%ws)
            nf = ws%nfree
            t = me%tout
            ! kinematics and element loads at the interpolated state; xddot
            ! from the Hermite interpolant of the step's end points (HERMITE)
            ! or by the articulated-body solve there (SOLVE); a dump needs a
            ! full evaluation
            call me%integ%interpolate(t, y)
            call set_element_states(me%sys%model, ws, y)
            if (cs%output_xdd == 'SOLVE') then
                call dynamics_outputs(me%sys%model, ws, t, y(1:nf), y(nf + 1:2*nf), stat)
            else
                call interpolate_hermite(me%integ, t, yh, dydt)
                call dynamics_outputs(me%sys%model, ws, t, y(1:nf), y(nf + 1:2*nf), stat, dydt(nf + 1:2*nf))
            end if
            if (stat /= stat_ok) then
                call me%fail(exit_diverged, 'run stopped: singular joint at an output time')
                return
            end if
            if (me%kd <= size(cs%dump_times)) then
                if (abs(t - cs%dump_times(me%kd)) <= me%tol) then
                    me%nev_out = me%nev_out + 1
                    call me%sys%rhs(t, y, dydt, stat, msg)
                    if (stat /= stat_ok) then
                        call me%fail(exit_diverged, 'run stopped: '//trim(msg))
                        return
                    end if
                end if
            end if
            en = energy_terms(me%sys%model, ws, energy_integrals(y))
            call channels_compute(cs, ws, t, en, me%ch)
            call me%track_peaks(t)
            if (abs(t - (cs%t_start + me%ks*cs%sample_dt)) <= me%tol) call me%record_sample(t)
            if (abs(t - (cs%t_start + me%kp*cs%print_dt)) <= me%tol) then
                if (.not. me%rated) then
                    me%res%nrows = me%res%nrows + 1
                    call me%rows%add([t, me%ch%value])
                end if
                me%kp = me%kp + 1
                call me%out%flush(me%ch)
            end if
            if (me%kd <= size(cs%dump_times)) then
                if (abs(t - cs%dump_times(me%kd)) <= me%tol) then
                    if (me%out%active) call dump_record(me%out%h5, me%sys%model, ws, t, stat, msg)
                    me%kd = me%kd + 1
                end if
            end if
            me%res%t_reached = t
            if (t >= cs%t_end - me%tol) me%running = .false.
        end associate
    end subroutine run_output

    !> One sample: the result file, the assessment inputs and, when kept,
    !! the in-memory copy.
    subroutine record_sample(me, t)
        class(run_state_t), intent(inout) :: me
        real(wp), intent(in) :: t
        integer :: k
        call me%out%sample(t, me%ch, me%sys%ws)
        if (me%out%failed()) call me%fail(exit_output, me%out%error())
        me%ks = me%ks + 1
        k = me%ks
        if (.not. me%rated) call me%crit%add([me%ch%value(me%icol), me%ch%head_x_acc(1:2)])
        if (me%keep) then
            me%res%samples_t(k) = t
            me%res%samples(:, k) = me%ch%value
            me%res%samples_head_s(:, :, k) = me%sys%ws%kin%s(:, :, me%cs%head)
        end if
    end subroutine record_sample

    !> Sign changes of the switching functions in the last step: locate the
    !! first one (Illinois regula falsi on the dense output), redo the step
    !! up to it and restart there.
    subroutine run_locate_events(me, stat, msg)
        class(run_state_t), intent(inout) :: me
        integer, intent(out) :: stat                  !! stat_ok, or the failure of an evaluation or step
        character(len=msglen), intent(out) :: msg     !! why it failed
        real(wp) :: ta, tb, tc, ga, gb, gc, t0, side
        real(wp), dimension(size(me%ygood)) :: y0, yc, fc
        real(wp) :: sw_new(me%nsw)
        integer :: k, kev, it
        stat = stat_ok; msg = ''
        associate (integ => me%integ, sys => me%sys)
            call switching_functions(sys%model, integ%current_time(), sys%ws%kin, sys%ws%x, sw_new)
            kev = 0
            do k = 1, me%nsw
                if (sign(one, me%sw_old(k)) /= sign(one, sw_new(k)) .and. abs(me%sw_old(k)) > switch_deadband &
                    .and. abs(sw_new(k)) > switch_deadband) then
                    kev = k
                    exit
                end if
            end do
            if (kev == 0 .or. integ%current_time() - integ%previous_time() < event_min_step) then
                me%sw_old = sw_new
                return
            end if
            side = sign(one, sw_new(kev))
            ta = integ%previous_time(); tb = integ%current_time(); ga = me%sw_old(kev); gb = sw_new(kev)
            t0 = integ%previous_time(); y0 = integ%previous_state()
            tc = tb
            do it = 1, event_max_iter
                tc = tb - gb*(tb - ta)/(gb - ga)
                call integ%interpolate(tc, yc)
                call sys%rhs(tc, yc, fc, stat, msg)
                if (stat /= stat_ok) return
                call switching_functions(sys%model, tc, sys%ws%kin, sys%ws%x, sw_new)
                gc = sw_new(kev)
                if (abs(tb - ta) < event_width) exit
                if (sign(one, gc) == sign(one, gb)) then
                    tb = tc; gb = gc; ga = 0.5_wp*ga
                else
                    ta = tb; ga = gb; tb = tc; gb = gc
                end if
            end do
            if (tc - t0 < event_width .or. tb - tc < zero) then
                me%sw_old = sw_new          ! no room to land before it: take the step as it is
                return
            end if
            ! redo the step from its start to the switching time; restart there
            ! before the next step
            call integ%init(sys, t0, y0, stat, msg)
            if (stat /= stat_ok) return
            if (me%tout > t0 .and. me%tout < tc) then
                ! keep the pending output time on a step end so it can still be interpolated
                call integ%advance(sys, me%tout, yc, me%tout, stat, msg)
                if (stat /= stat_ok) return
            end if
            call integ%advance(sys, tc, yc, tc, stat, msg)
            if (stat /= stat_ok) return
            me%pending_restart = .true.
            me%res%nevents = me%res%nevents + 1
            call switching_functions(sys%model, integ%current_time(), sys%ws%kin, sys%ws%x, me%sw_old)
            me%sw_old(kev) = side*max(abs(me%sw_old(kev)), tiny(one))   ! this switch has happened
        end associate
    end subroutine run_locate_events

    !> The accepted state must be finite and keep the energy balance.
    subroutine check_state(me, stat, msg)
        class(run_state_t), intent(inout) :: me
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        type(energy_t) :: e
        real(wp) :: scale, resid
        real(wp), allocatable :: y(:)
        stat = stat_ok; msg = ''
        y = me%integ%current_state()
        associate (en0 => me%en0, res => me%res)
            if (.not. all(abs(y) <= huge(1.0_wp))) then
                stat = stat_not_finite
                write (msg, '(a,es12.5,a)') 'the state became NaN or infinite at t = ', me%integ%current_time(), ' s'
                return
            end if
            e = energy_terms(me%sys%model, me%sys%ws, energy_integrals(y))
            ! the scale is the energy of the deformation-level motion: the kinetic
            ! energy relative to the root's translation and the element, gravity
            ! and applied energies (not the work of driving the whole model along)
            scale = e%kinetic_rel + abs(e%gravity - en0%gravity) + abs(e%elastic) + abs(e%hold - en0%hold) + &
                    abs(e%dissipated) + abs(e%muscle) + abs(e%applied)
            res%energy_scale = max(res%energy_scale, scale)
            resid = abs(e%total - me%ch%e0)
            res%energy_residual = max(res%energy_residual, resid)
            if (resid > energy_fail_fraction*res%energy_scale + energy_fail_floor) then
                stat = stat_energy_lost
                write (msg, '(a,es12.5,a,es10.3,a,es10.3,a)') 'the energy balance was lost at t = ', &
                    me%integ%current_time(), &
                    ' s (residual ', resid, ' J against energy flows of ', res%energy_scale, &
                    ' J): the solution is growing without a physical cause'
            end if
        end associate
    end subroutine check_state

    !> For a fixed-step method: the likely cause of a failure and a step that
    !! would be stable, from the spectral radius at the last good state.
    function diagnosis(me) result(s)
        class(run_state_t), intent(inout) :: me
        character(len=:), allocatable :: s
        real(wp) :: rho, limit
        integer :: lead, st, nf
        character(len=msglen) :: m
        character(len=400) :: buf
        s = ''
        limit = me%integ%stability_limit()
        if (limit >= huge(1.0_wp)) return
        call spectral_radius(me%sys, me%tgood, me%ygood, rho, lead, st, m)
        if (st /= stat_ok .or. rho <= zero) return
        nf = me%sys%ws%nfree
        associate (cs => me%cs)
            write (buf, '(3a,es9.2,a,es10.3,a,a,a,f7.2,a,f5.2,a,es9.2,a)') '. Likely cause: ', &
                trim(cs%integrator), ' with step ', cs%h, ' s is at or beyond its stability limit: the fastest '// &
                'mode has |lambda| = ', rho, ' 1/s, mostly in ', &
                trim(dof_label(cs%model%tree, me%sys%ws%ifree(1 + mod(lead - 1, nf)))), &
                ' (h |lambda| = ', cs%h*rho, ' at the last good state; limit ', limit, &
                '); use a step below ', stable_step_margin*limit/rho, &
                ' s, an error-controlled method (DOPRI5, ADAMS) or the stiff ROS34PW2'
        end associate
        s = trim(buf)
    end function diagnosis

    !> Mark the run stopped with an exit code and message.
    subroutine fail(me, code, text)
        class(run_state_t), intent(inout) :: me
        integer, intent(in) :: code
        character(len=*), intent(in) :: text
        me%res%exit_code = code
        me%res%status = 'incomplete'
        me%res%message = text
        me%running = .false.
    end subroutine fail

    subroutine track_peaks(me, t)
        class(run_state_t), intent(inout) :: me
        real(wp), intent(in) :: t
        integer :: k, f
        real(wp), allocatable :: e(:)
        do f = 1, size(me%mon)
            if (size(me%mon(f)%peak) == 0) cycle
            allocate (e(size(me%mon(f)%peak)))
            call me%cs%model%family(f)%f%monitor(me%sys%ws%x, e)
            where (e > me%mon(f)%peak)
                me%mon(f)%time = t
                me%mon(f)%peak = e
            end where
            deallocate (e)
        end do
        do k = 1, me%ch%n
            if (me%ch%value(k) > me%peaks%vmax(k)) then
                me%peaks%vmax(k) = me%ch%value(k); me%peaks%tmax(k) = t
            end if
            if (me%ch%value(k) < me%peaks%vmin(k)) then
                me%peaks%vmin(k) = me%ch%value(k); me%peaks%tmin(k) = t
            end if
        end do
    end subroutine track_peaks

    !> Injury assessment, listing tables, peaks, energy balance and the
    !! end-of-run lines; close the result file with its status. res is the
    !! run's result.
    subroutine run_finish(me, res)
        class(run_state_t), intent(inout) :: me
        type(run_result_t), intent(out) :: res         !! what happened
        character(len=msglen) :: line, note
        integer :: st
        integer(i8) :: c1, rate
        type(criteria_input_t) :: hist
        real(wp), allocatable :: cols(:, :)
        integer :: k
        call me%prog%finish()
        call system_clock(c1, rate)
        if (me%clock0 > 0) me%res%wall = real(c1 - me%clock0, wp)/real(rate, wp)
        me%res%nevals_output = me%nev_out
        allocate (me%res%range_peak(0))
        if (allocated(me%mon)) then
            do k = 1, size(me%mon)
                me%res%range_peak = [me%res%range_peak, me%mon(k)%peak]
            end do
        end if
        me%res%nevals = me%sys%nevals - me%nev_out
        if (allocated(me%integ)) then
            me%res%nsteps = me%integ%steps()
            me%res%nreject = me%integ%rejected()
            me%res%njac = me%integ%jacobians()
            me%res%nfact = me%integ%factorizations()
        end if
        if (me%keep .and. allocated(me%res%samples_t)) then
            me%res%samples_t = me%res%samples_t(1:me%ks)
            me%res%samples = me%res%samples(:, 1:me%ks)
            me%res%samples_head_s = me%res%samples_head_s(:, :, 1:me%ks)
        end if
        if (me%rows%m > 0 .and. .not. me%rated) then
            allocate (cols(me%crit%n, ncriteria_columns))
            do k = 1, ncriteria_columns
                cols(:, k) = me%crit%column(k)
            end do
            hist = criteria_input_from(cols)
            call me%crit%clear()
            call assess(me%cs%t_start, me%cs%sample_dt, hist, me%ks, me%res%criteria, me%cs%occupant, &
                        me%cs%nic_frame)
            call me%lst%histories(me%ch, me%rows, me%cs, me%peaks%vmax, me%peaks%vmin)
            call me%rows%clear()
            call me%lst%peaks(me%ch, me%peaks%vmax, me%peaks%tmax, me%peaks%vmin, me%peaks%tmin)
            call me%lst%criteria(me%res%criteria)
            call me%out%criteria(me%res%criteria)
            call range_report(me)
        end if
        call end_of_run_lines(me)
        call me%out%counts(me%res%nsteps, me%res%nreject, me%res%nevals, me%res%nevals_output, me%res%njac, &
                           me%res%nfact)
        call me%out%close(me%ch, trim(me%res%status), trim(me%res%message), st, line, note)
        if (st /= stat_ok) call me%fail(exit_output, trim(line))
        if (len_trim(note) > 0 .and. len_trim(me%res%file_note) > 0) then
            me%res%file_note = trim(me%res%file_note)//'; '//note
        else if (len_trim(note) > 0) then
            me%res%file_note = note
        end if
        me%running = .false.
        res = me%res
    end subroutine run_finish

    !> The families' run monitors report: their lines in the listing, the
    !! first one's warning as the run's (stderr) unless it has one already.
    subroutine range_report(me)
        type(run_state_t), intent(inout) :: me
        character(len=160), allocatable :: lines(:)
        character(len=:), allocatable :: summary
        integer :: k, f
        if (.not. allocated(me%mon)) return
        do f = 1, size(me%mon)
            if (size(me%mon(f)%peak) == 0) cycle
            call me%cs%model%family(f)%f%monitor_report(me%mon(f)%peak, me%mon(f)%time, lines, summary)
            do k = 1, size(lines)
                call me%lst%message(lines(k))
            end do
            if (len(summary) > 0 .and. len_trim(me%res%warning) == 0) me%res%warning = summary
        end do
    end subroutine range_report

    !> The energy balance, an accuracy warning, the counts and the status
    !! in the listing.
    subroutine end_of_run_lines(me)
        type(run_state_t), intent(inout) :: me
        character(len=msglen) :: line
        associate (res => me%res)
            write (line, '(a,es11.4,a,es10.3,a,es10.3,a)') 'ENERGY BALANCE: TOTAL AT START ', me%ch%e0, &
                ' J; LARGEST RESIDUAL ', res%energy_residual, ' J AGAINST ENERGY FLOWS OF ', res%energy_scale, ' J'
            call me%lst%message(line)
            if (res%energy_residual > energy_warn_fraction*res%energy_scale .and. res%exit_code == exit_ok) then
                write (res%warning, '(a,f6.1,a)') 'WARNING: the energy balance is off by ', &
                    100*res%energy_residual/max(res%energy_scale, tiny(one)), &
                    ' % of the energy flows: the results are inaccurate; use a smaller step or tolerance'
                call me%lst%message(res%warning)
            end if
            write (line, '(a,f9.4,a,i0,a,i0,a,i0,a,i0,a,i0,a,f8.3,a)') 'END OF RUN AT T = ', res%t_reached, &
                ' S: ', res%nsteps, ' STEPS (', res%nreject, ' REJECTED, ', res%nevents, ' EVENTS), ', &
                res%nevals, ' DYNAMICS EVALUATIONS + ', res%nevals_output, ' AT OUTPUTS, ', res%wall, ' S WALL TIME'
            call me%lst%message(line)
            if (res%njac > 0 .or. res%nfact > 0) then
                write (line, '(a,i0,a,i0,a)') 'END OF RUN: ', res%njac, ' JACOBIANS AND ', res%nfact, &
                    ' FACTORIZATIONS OF THE ITERATION MATRIX'
                call me%lst%message(line)
            end if
            if (res%exit_code /= exit_ok) call me%lst%message('RUN INCOMPLETE: '//trim(res%message))
        end associate
    end subroutine end_of_run_lines

end module hn_run
