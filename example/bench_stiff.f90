!> Benchmark (not a test) of whole runs: for the NBDL 15 g sled, the
!! forehead impact 6-2 and case 6-2 with every element stiffness x100
!! (first 30 ms), each candidate setting against a DOPRI5 rtol 1e-10
!! reference: head rotation error [deg], evaluations, Jacobians,
!! factorizations, wall time of the run loop with HDF5 output every
!! 0.1 ms, real-time factor (simulated / wall) and the ratio of the wall
!! time of ADAMS rtol 1e-4 (run alternately with it, same session) to the
!! candidate's. Wall times are the best of `nrep` alternating runs.
!! Also the difference of the head accelerations obtained from the
!! derivative of the dense output and of the step's Hermite interpolant
!! (the run's output path) against a full evaluation at the same states,
!! and the head and OC channels of both output paths against the
!! reference.
!!
!!   fpm run --example bench_stiff --profile release
program bench_stiff
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    use hn_dynamics, only: model_ode_t, model_ode_init, state_size, coordinates_to_state, dynamics_outputs
    use hn_kinematics, only: body_accelerations
    use hn_integrators, only: integrator_t, new_integrator, interpolate_hermite
    use hn_kinds, only: g_std
    use bench_decks, only: read_stiffened_case, delete_file
    implicit none

    type :: config_t
        character(len=8) :: method
        real(wp) :: rtol
        character(len=8) :: jacobian = 'STRUCT'
        character(len=8) :: xdd = 'HERMITE'       !! accelerations at output times (OUTPUT card F2)
    end type config_t

    character(len=*), parameter :: h5tmp = 'bench_stiff_tmp.h5'
    integer :: nrep = 3
    character(len=16) :: arg

    ! an argument 'quick': NBDL only
    arg = ''
    if (command_argument_count() >= 1) call get_command_argument(1, arg)
    if (arg == 'quick') nrep = 3

    write (*, '(a)') 'case      method    rtol     Jacobian  err theta (deg)   evals  Jacs  facts  steps  rej' // &
        '   wall (s)   RTF   ADAMS 1e-4 / wall'
    call sweep('nbdl15g', 'input/nbdl15g.inp', 0.25_wp, 0.0_wp)
    call acceleration_check('ROS34PW2', 1.0e-3_wp)
    call acceleration_check('ADAMS', 1.0e-4_wp)
    call channel_check()
    if (arg /= 'quick') then
        call sweep('case6-2', 'input/case6-2.inp', 0.1_wp, 0.0_wp)
        call sweep('stiff6-2', 'input/case6-2.inp', 0.03_wp, 100.0_wp)
    end if
    call delete_file(h5tmp)

contains

    subroutine sweep(label, deck, t_end, stiffen)
        character(len=*), intent(in) :: label, deck
        real(wp), intent(in) :: t_end, stiffen
        type(config_t), allocatable :: configs(:)
        type(run_result_t) :: res, resa
        real(wp), allocatable :: th_ref(:)
        real(wp) :: eth, wall, wall_adams
        real(wp), allocatable :: walls(:), errs(:)
        type(run_result_t), allocatable :: results(:)
        integer :: k, r, ith

        configs = [config_t('ROS34PW2', 1.0e-2_wp), config_t('ROS34PW2', 3.0e-3_wp), &
                   config_t('ROS34PW2', 1.0e-3_wp), config_t('ROS34PW2', 1.0e-4_wp), &
                   config_t('ROS34PW2', 1.0e-3_wp, 'FD'), config_t('ROS2', 1.0e-2_wp, 'FD'), &
                   config_t('ADAMS', 1.0e-4_wp)]
        allocate (walls(size(configs)), errs(size(configs)), results(size(configs)))
        call one_run(deck, t_end, stiffen, config_t('DOPRI5', 1.0e-10_wp), '', res, ith)
        th_ref = res%samples(ith, :)
        wall_adams = huge(1.0_wp)
        do k = 1, size(configs)
            wall = huge(1.0_wp)
            do r = 1, nrep
                ! ADAMS rtol 1e-4 alternately with the candidates (best of all its runs)
                if (k == 1 .or. k == size(configs) .or. r == 1) then
                    call one_run(deck, t_end, stiffen, config_t('ADAMS', 1.0e-4_wp), h5tmp, resa, ith)
                    wall_adams = min(wall_adams, resa%wall)
                end if
                call one_run(deck, t_end, stiffen, configs(k), h5tmp, res, ith)
                wall = min(wall, res%wall)
            end do
            eth = -1
            if (res%exit_code == 0) eth = maxval(abs(res%samples(ith, :) - th_ref))
            walls(k) = wall
            results(k) = res
            errs(k) = eth
        end do
        do k = 1, size(configs)
            write (*, '(a9,1x,a8,es9.1,2x,a8,es14.3,i9,i6,i7,i7,i5,f11.4,f7.2,f10.1)') label, configs(k)%method, &
                configs(k)%rtol, configs(k)%jacobian, errs(k), results(k)%nevals, results(k)%njac, results(k)%nfact, &
                results(k)%nsteps, results(k)%nreject, walls(k), t_end/walls(k), wall_adams/walls(k)
        end do
        flush (6)
    end subroutine sweep

    !> Head acceleration at every 0.1 ms sample of the NBDL run from the
    !! derivative of the method's own dense output and from the derivative of
    !! the cubic Hermite interpolant of the step's end points (the run's
    !! output path, OUTPUT ... HERMITE) against a full evaluation at the same
    !! interpolated state (OUTPUT ... SOLVE): largest difference in g and
    !! rad/s^2 and relative to the largest head acceleration.
    subroutine acceleration_check(method, rtol)
        character(len=*), intent(in) :: method
        real(wp), intent(in) :: rtol
        type(case_t) :: cs
        type(model_ode_t) :: sys
        class(integrator_t), allocatable :: integ
        real(wp), allocatable :: y(:), yh(:), dydt(:), dh(:), f(:)
        real(wp) :: t, a_full(3), w_full(3), da(2), dw(2), amax, wmax, ak(3), wk(3)
        integer :: stat, nf, k, h, m
        character(len=msglen) :: msg
        character(len=*), parameter :: label(2) = [character(len=12) :: 'dense output', 'Hermite']
        call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
        if (stat /= 0) error stop trim(msg)
        call model_ode_init(sys, cs%model)
        nf = sys%ws%nfree
        h = cs%head
        allocate (y(state_size(sys)), yh(state_size(sys)), dydt(state_size(sys)), dh(state_size(sys)), &
                  f(state_size(sys)))
        call coordinates_to_state(sys%ws, cs%x0, cs%xd0, y)
        call new_integrator(method, integ, stat)
        call integ%set_step(cs%h)
        call integ%set_tolerances(rtol, rtol*1.0e-2_wp)
        call integ%init(sys, cs%t_start, y, stat, msg)
        da = 0; dw = 0; amax = 0; wmax = 0
        do k = 1, 2500
            t = cs%t_start + 1.0e-4_wp*k
            call integ%advance(sys, t, y, cs%t_end, stat, msg)
            if (stat /= 0) error stop trim(msg)
            call integ%interpolate(t, y, dydt)
            call interpolate_hermite(integ, t, yh, dh)
            call sys%rhs(t, y, f, stat, msg)
            call head_acceleration(sys, h, t, y, f, a_full, w_full)
            amax = max(amax, norm2(a_full)); wmax = max(wmax, norm2(w_full))
            do m = 1, 2
                if (m == 1) call head_acceleration(sys, h, t, y, dydt, ak, wk)
                if (m == 2) call head_acceleration(sys, h, t, y, dh, ak, wk)
                da(m) = max(da(m), norm2(ak - a_full)); dw(m) = max(dw(m), norm2(wk - w_full))
            end do
        end do
        do m = 1, 2
            write (*, '(a,a,a,es8.1,a,a12,a,es10.3,a,es10.3,a,es10.3,a,es10.3,a)') 'nbdl15g head acceleration ', &
                trim(method), ' rtol ', rtol, ' from the ', label(m), ' against a full evaluation: linear ', &
                da(m)/g_std, ' g (', da(m)/amax, ' of the peak), angular ', dw(m), ' rad/s^2 (', dw(m)/wmax, &
                ' of the peak)'
        end do
    end subroutine acceleration_check

    !> Head linear and angular acceleration at the interpolated state y
    !! with xddot_F taken from d.
    subroutine head_acceleration(sys, head, t, y, d, a, w)
        type(model_ode_t), intent(inout) :: sys
        integer, intent(in) :: head
        real(wp), intent(in) :: t, y(:), d(:)
        real(wp), intent(out) :: a(3), w(3)
        real(wp), allocatable :: acc(:, :), alpha(:, :)
        integer :: nf, stat
        nf = sys%ws%nfree
        allocate (acc(3, sys%model%tree%nbody), alpha(3, sys%model%tree%nbody))
        call dynamics_outputs(sys%model, sys%ws, t, y(1:nf), y(nf + 1:2*nf), stat, d(nf + 1:2*nf))
        call body_accelerations(sys%model%tree, sys%ws%kin, sys%ws%xdd, acc, alpha)
        a = acc(:, head); w = alpha(:, head)
    end subroutine head_acceleration

    !> The head and OC channels of the NBDL run with ROS34PW2 rtol 1e-3
    !! against the DOPRI5 rtol 1e-10 reference, with the output
    !! accelerations by HERMITE and by SOLVE: largest difference over the
    !! samples relative to the channel's largest magnitude in the reference.
    subroutine channel_check()
        character(len=*), parameter :: names(6) = [character(len=10) :: 'HEAD_AX', 'HEAD_AZ', 'HEAD_ALPHY', &
                                                                       'OC_FX', 'OC_FZ', 'OC_MY']
        type(run_result_t) :: ref, res
        type(case_t) :: cs
        type(channel_set_t) :: ch
        integer :: ith, m, j, ic, stat
        character(len=msglen) :: msg
        character(len=8), parameter :: modes(2) = [character(len=8) :: 'HERMITE', 'SOLVE']
        real(wp) :: e(size(names))
        call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
        call channels_define(cs, ch)
        call one_run('input/nbdl15g.inp', 0.25_wp, 0.0_wp, config_t('DOPRI5', 1.0e-10_wp), '', ref, ith)
        do m = 1, 2
            call one_run('input/nbdl15g.inp', 0.25_wp, 0.0_wp, config_t('ROS34PW2', 1.0e-3_wp, 'STRUCT', modes(m)), &
                         '', res, ith)
            do j = 1, size(names)
                ic = findloc(ch%name, names(j), dim=1)
                e(j) = maxval(abs(res%samples(ic, :) - ref%samples(ic, :)))/maxval(abs(ref%samples(ic, :)))
            end do
            write (*, '(a,a8,a,*(1x,a,es10.3))') 'nbdl15g ROS34PW2 rtol 1e-3, OUTPUT ', modes(m), &
                ' against DOPRI5 1e-10, largest difference / peak:', (trim(names(j)), e(j), j=1, size(names))
        end do
    end subroutine channel_check

    !> One run of `deck` to t_end with configuration cfg, samples kept,
    !! HDF5 written to h5name ('' for none).
    subroutine one_run(deck, t_end, stiffen, cfg, h5name, r, i_th)
        character(len=*), intent(in) :: deck, h5name
        real(wp), intent(in) :: t_end, stiffen
        type(config_t), intent(in) :: cfg
        type(run_result_t), intent(out) :: r
        integer, intent(out) :: i_th
        type(case_t) :: cs
        type(channel_set_t) :: ch
        integer :: lu
        character(len=*), parameter :: tmp = 'bench_stiff_deck.inp'
        call read_stiffened_case(deck, tmp, stiffen, cs)
        cs%integrator = cfg%method
        cs%rtol = cfg%rtol
        cs%atol = cfg%rtol*1.0e-2_wp
        cs%model%jacobian = cfg%jacobian
        cs%output_xdd = cfg%xdd
        cs%t_end = t_end
        cs%print_dt = t_end/10
        call channels_define(cs, ch)
        i_th = findloc(ch%name, 'HEAD_THETY', dim=1)
        open (newunit=lu, file='/dev/null', action='write')
        block
            type(run_state_t) :: run
            call run%execute(cs, lu, h5name, r, keep_samples=.true.)
        end block
        close (lu)
    end subroutine one_run

end program bench_stiff
