!> Running a case: initial state, posture holding, the integrator taking
!! its own steps, steps landing on the breakpoints of the input tables (and,
!! on request, on the switching points of the one-way elements), outputs
!! interpolated at the sample, print and dump times, the energy audit, and
!! the checks that stop a diverging run with a message: state not finite,
!! energy balance lost, a_ij singular, integrator failure.
module hn_run
    use hn_kinds, only: wp, zero, one, msglen, i8
    use hn_status, only: stat_ok, stat_not_finite, stat_energy_lost
    use hn_case, only: case_t
    use hn_dynamics, only: model_ode_t, model_ode_init, coordinates_to_state, state_size, energy_terms, &
                           energy_t, nenergy
    use hn_forces, only: switch_count, switching_functions
    use hn_integrators, only: integrator_t, new_integrator, spectral_radius
    use hn_channels, only: channel_set_t, channels_define, channels_compute
    use hn_results, only: results_t
    use hn_listing, only: listing_t
    use hn_dump, only: dump_record
    use hn_breakpoints, only: case_breakpoints
    use hn_tree, only: dof_label
    use hn_assessment, only: assessment_t, assess, criteria_channels
    use hn_signals, only: signal_received
    use hn_version, only: code_version
    use hn_joint_limits, only: range_track, range_warnings, range_margin
    implicit none
    private

    public :: run_case, run_result_t

    real(wp), parameter :: switch_deadband = 1.0e-8_wp   !! |switching function| treated as zero

    integer, parameter, public :: exit_ok = 0, exit_usage = 1, exit_deck = 2, exit_diverged = 3, &
                                  exit_output = 4, exit_interrupted = 5, &
                                  exit_members_failed = 6

    !> What happened in a run.
    type :: run_result_t
        integer :: exit_code = exit_ok
        character(len=12) :: status = 'complete'
        character(len=msglen) :: message = ''
        character(len=msglen) :: warning = ''   !! a complete run whose results are doubtful
        real(wp) :: t_reached = zero
        integer :: nevals = 0            !! dynamics evaluations of the integrator
        integer :: nevals_output = 0     !! evaluations at output times
        integer :: nsteps = 0, nreject = 0, nevents = 0, njac = 0
        real(wp) :: wall = zero          !! wall-clock time of the run loop [s]
        real(wp) :: energy_residual = zero   !! largest |energy balance residual| [J]
        real(wp) :: energy_scale = zero      !! largest sum of energy-term magnitudes [J]
        real(wp), allocatable :: times(:), rows(:, :)   !! the listing rows
        integer :: nrows = 0
        real(wp), allocatable :: samples_t(:), samples(:, :)  !! (optional) every channel at every sample
        type(assessment_t) :: criteria                   !! injury criteria of the run
    end type run_result_t

contains

    !> Run the case, writing the listing on unit `lu` and results to
    !! `h5name` ('' for none). With keep_samples, every channel at every
    !! sample is also returned in res (benchmarks).
    subroutine run_case(cs, lu, h5name, res, keep_samples)
        type(case_t), intent(inout) :: cs
        integer, intent(in) :: lu
        character(len=*), intent(in) :: h5name
        type(run_result_t), intent(out) :: res
        logical, intent(in), optional :: keep_samples
        type(model_ode_t) :: sys
        class(integrator_t), allocatable :: integ
        type(channel_set_t) :: ch
        type(results_t) :: out
        type(listing_t) :: lst
        type(energy_t) :: en, en0
        real(wp), allocatable :: y(:), dydt(:), ygood(:), vmax(:), vmin(:), tmax(:), tmin(:), tb(:)
        real(wp), allocatable :: sw_old(:), sw_new(:), crit_hist(:, :), rom_peak(:), rom_time(:)
        integer :: icrit(size(criteria_channels)), k
        real(wp) :: t, tout, tol, tstop, tgood
        integer :: stat, nf, ks, kp, kd, ib, nprint_max, nsw, nsample_max, nev_out0
        integer(i8) :: c0, c1, rate
        character(len=msglen) :: msg
        logical :: do_sample, do_print, do_dump, keep, pending_restart

        keep = .false.
        if (present(keep_samples)) keep = keep_samples
        call lst%start(lu, cs%model%title, code_version)
        call lst%echo_deck(cs%deck)
        call channels_define(cs, ch)
        call model_ode_init(sys, cs%model)
        nf = sys%ws%nfree
        allocate (y(state_size(sys)), dydt(state_size(sys)))
        call coordinates_to_state(sys%ws, cs%x0, cs%xd0, y)
        t = cs%t_start

        if (cs%hold_posture) then
            call sys%rhs(t, y, dydt, stat, msg)
            if (stat /= 0) then
                call fail(exit_diverged, 'posture holding: '//trim(msg)); call finish(); return
            end if
            sys%model%q_hold(sys%ws%ifree) = -matmul(sys%ws%a(sys%ws%ifree, sys%ws%ifree), dydt(nf + 1:2*nf))
            cs%model%q_hold = sys%model%q_hold
        end if
        call lst%model_summary(cs)

        call new_integrator(cs%integrator, integ, stat)
        integ%h = cs%h
        integ%rtol = cs%rtol
        integ%atol = cs%atol
        call integ%init(sys, t, y, stat, msg)
        if (stat /= 0) then
            call fail(exit_diverged, trim(msg)); call finish(); return
        end if
        en0 = energy_terms(sys%model, sys%ws, y(2*nf + 1:))
        ch%e0 = en0%total
        ch%head_r0 = sys%ws%kin%r(:, cs%head) - sys%ws%kin%r(:, cs%t1)
        ch%t1_r0 = sys%ws%kin%r(:, cs%t1)
        if (len_trim(h5name) > 0) then
            call out%open(cs, ch, trim(h5name), code_version, stat, msg)
            if (stat /= 0) then
                call fail(exit_output, trim(msg)); return
            end if
        end if
        nprint_max = nint((cs%t_end - cs%t_start)/cs%print_dt) + 2
        allocate (res%times(nprint_max), res%rows(ch%n, nprint_max))
        if (keep) then
            nsample_max = nint((cs%t_end - cs%t_start)/cs%sample_dt) + 2
            allocate (res%samples_t(nsample_max), res%samples(ch%n, nsample_max))
        end if
        allocate (crit_hist(nint((cs%t_end - cs%t_start)/cs%sample_dt) + 2, size(criteria_channels)))
        do k = 1, size(criteria_channels)
            icrit(k) = findloc(ch%name, criteria_channels(k), dim=1)
        end do
        allocate (vmax(ch%n), vmin(ch%n), tmax(ch%n), tmin(ch%n))
        vmax = -huge(1.0_wp); vmin = huge(1.0_wp); tmax = t; tmin = t
        allocate (rom_peak(size(cs%model%ranges)), rom_time(size(cs%model%ranges)))
        rom_peak = zero; rom_time = t

        tb = [real(wp) ::]
        if (cs%events /= 'NONE') tb = case_breakpoints(cs)
        nsw = 0
        if (cs%events == 'STATE') nsw = switch_count(cs%model)
        allocate (sw_old(nsw), sw_new(nsw))
        if (nsw > 0) call switching_functions(sys%model, t, sys%ws%kin, sys%ws%x, sw_old)
        ib = 1
        tgood = t
        ygood = y
        tol = 1.0e-9_wp*max(cs%sample_dt, 1.0e-6_wp)
        ks = 0; kp = 0; kd = 1
        nev_out0 = 0
        pending_restart = .false.
        call system_clock(c0, rate)
        outputs: do
            tout = min(cs%t_start + ks*cs%sample_dt, cs%t_start + kp*cs%print_dt, cs%t_end)
            if (kd <= size(cs%dump_times)) tout = min(tout, cs%dump_times(kd))
            do while (integ%t < tout - tol)
                do while (ib <= size(tb))
                    if (tb(ib) > integ%t + tol) exit
                    ib = ib + 1
                end do
                tstop = cs%t_end
                if (ib <= size(tb)) tstop = min(tstop, tb(ib))
                ! a restart at a breakpoint or event waits until the next step, so
                ! that outputs inside the step that reached it can still be
                ! interpolated from that step
                if (pending_restart) then
                    call integ%restart(sys, stat, msg)
                    pending_restart = .false.
                end if
                call integ%step(sys, tstop, stat, msg)
                if (signal_received() /= 0) then
                    write (msg, '(a,i0,a,es12.5,a)') 'interrupted by signal ', signal_received(), ' at t = ', &
                        tgood, ' s'
                    call fail(exit_interrupted, trim(msg))
                    exit outputs
                end if
                if (stat == 0) call check_state(stat, msg)
                if (stat /= 0) then
                    call fail(exit_diverged, 'run stopped: '//trim(msg)//trim(diagnosis()))
                    exit outputs
                end if
                if (nsw > 0) then
                    call locate_events(stat, msg)
                    if (stat /= 0) then
                        call fail(exit_diverged, 'run stopped: '//trim(msg)); exit outputs
                    end if
                end if
                if (ib <= size(tb)) then
                    if (abs(integ%t - tb(ib)) <= tol) then
                        ! a kink or jump of an input: start the formulas afresh
                        pending_restart = .true.
                        ib = ib + 1
                    end if
                end if
                tgood = integ%t
                ygood = integ%y
            end do
            ! output at tout from the dense output of the last step
            t = tout
            call integ%interpolate(t, y)
            nev_out0 = nev_out0 + 1
            call sys%rhs(t, y, dydt, stat, msg)
            if (stat /= 0) then
                call fail(exit_diverged, 'run stopped: '//trim(msg)); exit outputs
            end if
            en = energy_terms(sys%model, sys%ws, y(2*nf + 1:))
            call channels_compute(cs, sys%ws, t, en, ch)
            call track_peaks()
            do_sample = abs(t - (cs%t_start + ks*cs%sample_dt)) <= tol
            do_print = abs(t - (cs%t_start + kp*cs%print_dt)) <= tol
            do_dump = .false.
            if (kd <= size(cs%dump_times)) do_dump = abs(t - cs%dump_times(kd)) <= tol
            if (do_sample) then
                call out%sample(t, ch, sys%ws)
                crit_hist(ks + 1, :) = ch%value(icrit)
                if (keep) then
                    res%samples_t(ks + 1) = t
                    res%samples(:, ks + 1) = ch%value
                end if
                ks = ks + 1
            end if
            if (do_print) then
                res%nrows = res%nrows + 1
                res%times(res%nrows) = t
                res%rows(:, res%nrows) = ch%value
                kp = kp + 1
                call out%flush(ch)
            end if
            if (do_dump) then
                if (out%active) call dump_record(out%h5, sys%model, sys%ws, t, stat, msg)
                kd = kd + 1
            end if
            res%t_reached = t
            if (t >= cs%t_end - tol) exit outputs
        end do outputs
        call system_clock(c1)
        res%wall = real(c1 - c0, wp)/real(rate, wp)
        res%nevals_output = nev_out0
        res%nevals = sys%nevals - nev_out0
        res%nsteps = integ%nsteps
        res%nreject = integ%nreject
        res%njac = integ%njac
        if (keep) then
            res%samples_t = res%samples_t(1:ks)
            res%samples = res%samples(:, 1:ks)
        end if
        call assess(cs%t_start, cs%sample_dt, crit_hist(1:ks, :), res%criteria)
        call finish()
    contains

        subroutine fail(code, text)
            integer, intent(in) :: code
            character(len=*), intent(in) :: text
            res%exit_code = code
            res%status = 'incomplete'
            res%message = text
        end subroutine fail

        !> Listing tables, peaks, energy balance and the end-of-run lines; close the file.
        subroutine finish()
            character(len=msglen) :: line
            integer :: st
            if (allocated(res%times)) then
                call lst%histories(ch, res%times, res%rows, res%nrows)
                call lst%peaks(ch, vmax, tmax, vmin, tmin)
                call lst%criteria(res%criteria)
                call out%criteria(res%criteria)
                call range_report()
            end if
            write (line, '(a,es11.4,a,es10.3,a,es10.3,a)') 'ENERGY BALANCE: TOTAL AT START ', ch%e0, &
                ' J; LARGEST RESIDUAL ', res%energy_residual, ' J AGAINST ENERGY FLOWS OF ', res%energy_scale, ' J'
            call lst%message(line)
            if (res%energy_residual > 0.01_wp*res%energy_scale .and. res%exit_code == exit_ok) then
                write (res%warning, '(a,f6.1,a)') 'WARNING: the energy balance is off by ', &
                    100*res%energy_residual/max(res%energy_scale, tiny(one)), &
                    ' % of the energy flows: the results are inaccurate; use a smaller step or tolerance'
                call lst%message(res%warning)
            end if
            write (line, '(a,f9.4,a,i0,a,i0,a,i0,a,i0,a,i0,a,f8.3,a)') 'END OF RUN AT T = ', res%t_reached, &
                ' S: ', res%nsteps, ' STEPS (', res%nreject, ' REJECTED, ', res%nevents, ' EVENTS), ', &
                res%nevals, ' DYNAMICS EVALUATIONS + ', res%nevals_output, ' AT OUTPUTS, ', res%wall, ' S WALL TIME'
            call lst%message(line)
            if (res%exit_code /= exit_ok) call lst%message('RUN INCOMPLETE: '//trim(res%message))
            call out%close(ch, trim(res%status), trim(res%message), st, line)
            if (st /= 0 .and. res%exit_code == exit_ok) call fail(exit_output, trim(line))
        end subroutine finish

        !> Joints past their physiological range by more than the margin: in
        !! the listing, and summed up in the run's warning (stderr).
        subroutine range_report()
            character(len=160), allocatable :: lines(:)
            integer :: k
            lines = range_warnings(cs%model%ranges, rom_peak, rom_time, range_margin)
            do k = 1, size(lines)
                call lst%message(lines(k))
            end do
            if (size(lines) == 0 .or. len_trim(res%warning) > 0) return
            k = count(rom_peak(1:maxloc(rom_peak, dim=1)) > range_margin)
            write (res%warning, '(a,i0,2a)') 'WARNING: ', size(lines), ' joint rotation(s) past the physiological '// &
                'range plus margin; largest: ', trim(lines(k)(16:))
        end subroutine range_report

        !> The accepted state must be finite and keep the energy balance.
        subroutine check_state(st, m)
            integer, intent(out) :: st
            character(len=msglen), intent(out) :: m
            type(energy_t) :: e
            real(wp) :: scale, resid
            st = stat_ok; m = ''
            if (.not. all(abs(integ%y) <= huge(1.0_wp))) then
                st = stat_not_finite
                write (m, '(a,es12.5,a)') 'the state became NaN or infinite at t = ', integ%t, ' s'
                return
            end if
            e = energy_terms(sys%model, sys%ws, integ%y(2*nf + 1:))
            ! the scale is the energy of the deformation-level motion: the kinetic
            ! energy relative to the root's translation and the element, gravity
            ! and applied energies (not the work of driving the whole model along)
            scale = e%kinetic_rel + abs(e%gravity - en0%gravity) + abs(e%elastic) + abs(e%hold - en0%hold) + &
                    abs(e%dissipated) + abs(e%muscle) + abs(e%applied)
            res%energy_scale = max(res%energy_scale, scale)
            resid = abs(e%total - ch%e0)
            res%energy_residual = max(res%energy_residual, resid)
            if (resid > 0.5_wp*res%energy_scale + 1.0e-3_wp) then
                st = stat_energy_lost
                write (m, '(a,es12.5,a,es10.3,a,es10.3,a)') 'the energy balance was lost at t = ', integ%t, &
                    ' s (residual ', resid, ' J against energy flows of ', res%energy_scale, &
                    ' J): the solution is growing without a physical cause'
            end if
        end subroutine check_state

        !> For a fixed-step method: the likely cause of the failure and a step
        !! that would be stable, from the spectral radius at the last good state.
        function diagnosis() result(s)
            character(len=:), allocatable :: s
            real(wp) :: rho, limit
            integer :: lead, st
            character(len=msglen) :: m
            character(len=400) :: buf
            s = ''
            limit = integ%stability_limit()
            if (limit >= huge(1.0_wp)) return
            call spectral_radius(sys, tgood, ygood, rho, lead, st, m)
            if (st /= 0 .or. rho <= zero) return
            write (buf, '(3a,es9.2,a,es10.3,a,a,a,f7.2,a,f5.2,a,es9.2,a)') '. Likely cause: ', &
                trim(cs%integrator), ' with step ', cs%h, ' s is at or beyond its stability limit: the fastest '// &
                'mode has |lambda| = ', rho, ' 1/s, mostly in ', trim(dof_label(cs%model%tree, &
                sys%ws%ifree(1 + mod(lead - 1, nf)))), ' (h |lambda| = ', cs%h*rho, ' at the last good state; limit ', limit, &
                '); use a step below ', 0.8_wp*limit/rho, ' s, an error-controlled method (DOPRI5, ADAMS) or ROS2'
            s = trim(buf)
        end function diagnosis

        !> Sign changes of the switching functions in the last step: locate
        !! the first one, redo the step up to it and restart there.
        subroutine locate_events(st, m)
            integer, intent(out) :: st
            character(len=msglen), intent(out) :: m
            real(wp) :: ta, tb_, tc, ga, gb, gc, t0, y0(size(y)), yc(size(y)), fc(size(y)), side
            integer :: k, kev, it
            st = 0; m = ''
            call switching_functions(sys%model, integ%t, sys%ws%kin, sys%ws%x, sw_new)
            kev = 0
            ! a sign change counts only between values clear of a dead band, so
            ! that a coordinate resting on its neutral value (roundoff noise)
            ! does not switch at every step
            do k = 1, nsw
                if (sign(one, sw_old(k)) /= sign(one, sw_new(k)) .and. abs(sw_old(k)) > switch_deadband .and. &
                    abs(sw_new(k)) > switch_deadband) then
                    kev = k
                    exit
                end if
            end do
            if (kev == 0 .or. integ%t - integ%told < 1.0e-9_wp) then
                sw_old = sw_new
                return
            end if
            ! Illinois regula falsi on the dense output for the first switch
            side = sign(one, sw_new(kev))
            ta = integ%told; tb_ = integ%t; ga = sw_old(kev); gb = sw_new(kev)
            t0 = integ%told; y0 = integ%yold
            tc = tb_
            do it = 1, 40
                tc = tb_ - gb*(tb_ - ta)/(gb - ga)
                call integ%interpolate(tc, yc)
                call sys%rhs(tc, yc, fc, st, m)
                if (st /= 0) return
                call switching_functions(sys%model, tc, sys%ws%kin, sys%ws%x, sw_new)
                gc = sw_new(kev)
                if (abs(tb_ - ta) < 1.0e-10_wp) exit
                if (sign(one, gc) == sign(one, gb)) then
                    tb_ = tc; gb = gc; ga = 0.5_wp*ga
                else
                    ta = tb_; ga = gb; tb_ = tc; gb = gc
                end if
            end do
            if (tc - t0 < 1.0e-10_wp .or. tb_ - tc < 0.0_wp) then
                sw_old = sw_new          ! no room to land before it: take the step as it is
                return
            end if
            ! redo the step from its start to the switching time; restart there
            ! before the next step
            call integ%init(sys, t0, y0, st, m)
            if (st /= 0) return
            if (tout > t0 .and. tout < tc) then
                ! keep the pending output time on a step end so it can still be interpolated
                call integ%advance(sys, tout, yc, tout, st, m)
                if (st /= 0) return
            end if
            call integ%advance(sys, tc, yc, tc, st, m)
            if (st /= 0) return
            pending_restart = .true.
            res%nevents = res%nevents + 1
            call switching_functions(sys%model, integ%t, sys%ws%kin, sys%ws%x, sw_old)
            sw_old(kev) = side*max(abs(sw_old(kev)), tiny(one))   ! this switch has happened
        end subroutine locate_events

        subroutine track_peaks()
            integer :: k
            call range_track(cs%model%ranges, sys%ws%x, t, rom_peak, rom_time)
            do k = 1, ch%n
                if (ch%value(k) > vmax(k)) then
                    vmax(k) = ch%value(k); tmax(k) = t
                end if
                if (ch%value(k) < vmin(k)) then
                    vmin(k) = ch%value(k); tmin(k) = t
                end if
            end do
        end subroutine track_peaks
    end subroutine run_case

end module hn_run
