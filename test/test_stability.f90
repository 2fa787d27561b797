!> Behaviour at the extremes: stiffened elements (x10, x100, x1000) under
!! the error-controlled and stiff methods, a fixed step beyond its
!! stability limit, large rotations, the Bryant-angle singularity, a long
!! run at rest, and the energy balance of a conservative deck.
program test_stability
    use hn_kinds, only: wp, msglen, deg
    use hn_case, only: case_t
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    use hn_testing, only: test_suite_t
    use hn_test_models, only: read_deck_lines
    implicit none

    type(test_suite_t) :: suite
    character(len=80), allocatable :: neck(:)

    ! a head on a two-joint neck: T1 held, C4, head; discs, ligaments,
    ! muscles, joint dampers; a forehead impact from 2 to 7 ms
    neck = [character(len=80) :: &
            'TITLE     THREE-BODY NECK FOR THE STABILITY TESTS', &
            'BODY      T1        R         20.0      0.3       0.25      0.2', &
            'BODY      C4        T1        0.5       0.0004    0.0004    0.0008', &
            'BODY      HEAD      C4        3.85      0.0166    0.0181    0.0120', &
            'JOINT     C4        0.0       0.0       0.02      0.0       0.0       -0.02', &
            'JOINT     HEAD      0.0       0.0       0.02      -0.02     0.0       -0.035', &
            'PRESCRIB  T1        TX        CONSTANT', 'PRESCRIB  T1        TY        CONSTANT', &
            'PRESCRIB  T1        TZ        CONSTANT', 'PRESCRIB  T1        RX        CONSTANT', &
            'PRESCRIB  T1        RY        CONSTANT', 'PRESCRIB  T1        RZ        CONSTANT', &
            'DISC      LOW       T1        C4        0.0003    0.005     8.33E6    16666.0', &
            '          0.0       0.0       0.0175    0.0       0.0       -0.0175', &
            '          2.0E6     1.65E-8   1.65E-8   3.4E-8    1.2', &
            'DISC      HIGH      C4        HEAD      0.0003    0.005     8.33E6    16666.0', &
            '          0.0       0.0       0.0175    -0.02     0.0       -0.0325', &
            '          2.0E6     1.65E-8   1.65E-8   3.4E-8    1.2', &
            'LIGAMENT  ALLOW     T1        C4        0.0       7.3E7     2.2', &
            '          0.009     0.0       0.015     0.009     0.0       -0.005', &
            'LIGAMENT  ISLLOW    T1        C4        0.0       8.5E7     2.84', &
            '          -0.04     0.0       0.014     -0.04     0.0       -0.006', &
            'MUSCLE    FRONT     T1        HEAD      40000.0   200.0', &
            '          0.06      0.0       -0.04     0.0       0.0       -0.03', &
            'MUSCLE    BACK      T1        HEAD      40000.0   200.0', &
            '          -0.05     0.0       -0.01     -0.08     0.0       -0.01', &
            'LIMIT     C4        RY        -20.0     20.0      0.05      100.0', &
            'LIMIT     HEAD      RY        -20.0     20.0      0.05      100.0', &
            'TABLE     IMPACT    5         0.001', &
            '          0.0       0.0       2.0       0.0       4.5       800.0', &
            '          7.0       0.0       200.0     0.0', &
            'FORCE     HEAD      R         IMPACT    -1.0      0.0       0.0', &
            '          0.095     0.0       0.03', &
            'HOLD      POSTURE']

    call test_stiffened('DOPRI5', 10.0_wp)
    call test_stiffened('ADAMS', 10.0_wp)
    call test_stiffened('ROS2', 10.0_wp)
    call test_stiffened('DOPRI5', 100.0_wp)
    call test_stiffened('ADAMS', 100.0_wp)
    call test_stiffened('ROS2', 100.0_wp)
    call test_stiffened('ROS2', 1000.0_wp)
    call test_stiffened('ADAMS', 1000.0_wp, 0.008_wp)
    call test_stiffened('DOPRI5', 1000.0_wp, 0.008_wp)
    call test_fixed_step_beyond_limit()
    call test_conservative_balance()
    call test_head_turned_half_round()
    call test_joint_through_90_singular()
    call test_joint_through_90_locked()
    call test_long_run_at_rest('ROS2', 10.0_wp)
    call test_long_run_at_rest('ADAMS', 1.0_wp)
    call suite%finish()

contains

    !> Run a deck given as lines plus a CONTROL card; the listing is discarded.
    subroutine run_lines(lines, control, res, ch)
        character(len=*), intent(in) :: lines(:), control
        type(run_result_t), intent(out) :: res
        type(channel_set_t), intent(out) :: ch
        type(case_t) :: cs
        character(len=msglen) :: msg
        integer :: u, stat
        call read_deck_lines('test_stability_scratch.inp', [character(len=max(len(lines), len(control))) :: lines, control], &
                             cs, stat, msg)
        if (stat /= 0) then
            res%exit_code = 2
            res%message = msg
            return
        end if
        call channels_define(cs, ch)
        open (newunit=u, file='/dev/null', action='write')
        block
            type(run_state_t) :: run
            call run%execute(cs, u, '', res, keep_samples=.true.)
        end block
        close (u)
    end subroutine run_lines

    character(len=80) function control(t_end, h, method, rtol) result(c)
        real(wp), intent(in) :: t_end, h, rtol
        character(len=*), intent(in) :: method
        write (c, '(a10,f10.5,es10.2,f10.5,a10,es10.2,es10.2)') 'CONTROL   ', t_end, h, t_end/10, method, rtol, rtol*1.0e-2_wp
    end function control

    subroutine test_stiffened(method, factor, t_end)
        character(len=*), intent(in) :: method
        real(wp), intent(in) :: factor
        real(wp), intent(in), optional :: t_end
        real(wp) :: te
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        character(len=160) :: d
        character(len=80) :: stiff
        te = 0.012_wp
        if (present(t_end)) te = t_end
        write (stiff, '(a10,f10.1)') 'STIFFEN   ', factor
        call run_lines([character(len=80) :: neck, stiff], control(te, 1.0e-5_wp, method, 1.0e-4_wp), res, ch)
        write (d, '(a,i0,a,es9.2,a,es9.2,a,i0,a,a)') 'exit ', res%exit_code, ', energy residual ', res%energy_residual, &
            ' J of ', res%energy_scale, ' J, ', res%nevals, ' evaluations ', trim(res%message)
        call suite%check(res%exit_code == 0 .and. res%energy_residual <= 1.0e-2_wp*res%energy_scale, &
                         trim(method)//' finishes with bounded energy, element stiffness x'//trim(adjustl(stiff(11:))), d)
    end subroutine test_stiffened

    !> RK4 at a step beyond its stability limit (stiffness x100): the run
    !! stops with a message naming the cause and a stable step, no NaN.
    subroutine test_fixed_step_beyond_limit()
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        call run_lines([character(len=80) :: neck, 'STIFFEN   100.0'], control(0.012_wp, 1.0e-4_wp, 'RK4', 1.0e-4_wp), &
                       res, ch)
        call suite%check(res%exit_code == 3 .and. index(res%message, 'stability limit') > 0 .and. &
                         index(res%message, 'use a step below') > 0 .and. all(abs(res%samples) <= huge(1.0_wp)), &
                         'RK4 beyond its stability limit stops with the cause and a suggested step', trim(res%message))
    end subroutine test_fixed_step_beyond_limit

    !> No dissipation, no muscles, no applied load, no prescribed motion:
    !! kinetic + gravity + elastic energy stays constant to the tolerance.
    subroutine test_conservative_balance()
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        character(len=80), allocatable :: deck(:)
        integer :: k, ib
        character(len=100) :: d
        deck = neck
        do k = 1, size(deck)
            if (deck(k)(1:4) == 'DISC') deck(k)(71:80) = '0.0'         ! no disc damping
            if (deck(k)(1:5) == 'FORCE') deck(k)(31:40) = 'NOLOAD'
        end do
        deck = [character(len=80) :: deck, 'FAMILY    MUSCLES   OFF', 'FAMILY    LIMITS    OFF', &
                'INITIAL   HEAD      RY        5.0       -200.0', 'INITIAL   C4        RX        2.0       100.0', &
                'TABLE     NOLOAD    1', '          0.0       0.0']
        call run_lines(deck, control(0.1_wp, 1.0e-4_wp, 'DOPRI5', 1.0e-9_wp), res, ch)
        ib = findloc(ch%name, 'E_BALANCE', dim=1)
        write (d, '(a,es9.2,a,es9.2,a)') 'largest |balance| ', maxval(abs(res%samples(ib, :))), ' J of ', &
            res%energy_scale, ' J'
        call suite%check(res%exit_code == 0 .and. maxval(abs(res%samples(ib, :))) < 1.0e-7_wp*res%energy_scale, &
                         'conservative deck: the energy balance closes to the tolerance (rtol 1e-9)', d)
    end subroutine test_conservative_balance

    !> The head turned 180 deg about the vertical (neutral and start), then
    !! struck: two methods agree and the energy balance closes.
    subroutine test_head_turned_half_round()
        type(run_result_t) :: r1, r2
        type(channel_set_t) :: ch
        character(len=80), allocatable :: deck(:)
        integer :: ith
        real(wp) :: diff
        character(len=120) :: d
        deck = [character(len=80) :: neck, 'NEUTRAL   HEAD      RZ        180.0']
        call run_lines(deck, control(0.05_wp, 1.0e-5_wp, 'DOPRI5', 1.0e-8_wp), r1, ch)
        call run_lines(deck, control(0.05_wp, 1.0e-5_wp, 'ADAMS', 1.0e-8_wp), r2, ch)
        ith = findloc(ch%name, 'HEAD_THETY', dim=1)
        diff = maxval(abs(r1%samples(ith, :) - r2%samples(ith, :)))
        write (d, '(a,es9.2,a,es9.2,a,f8.2,a)') 'DOPRI5 vs ADAMS head angle ', diff, ' deg; balance ', &
            r1%energy_residual, ' J; peak angle ', maxval(abs(r1%samples(ith, :))), ' deg'
        call suite%check(r1%exit_code == 0 .and. r2%exit_code == 0 .and. diff < 1.0e-4_wp .and. &
                         r1%energy_residual < 1.0e-5_wp*r1%energy_scale, &
                         'head turned 180 deg about the vertical: accurate (two methods agree, energy closes)', d)
    end subroutine test_head_turned_half_round

    !> C4's flexion angle driven to 120 deg with its RX and RZ free: the run
    !! stops at the Bryant-angle singularity with a clear message.
    subroutine test_joint_through_90_singular()
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        call run_lines([character(len=80) :: neck, 'PRESCRIB  C4        RY        HARMONIC  120.0     2.0'], &
                       control(0.2_wp, 1.0e-5_wp, 'DOPRI5', 1.0e-6_wp), res, ch)
        call suite%check(res%exit_code == 3 .and. index(res%message, 'Bryant-angle singularity') > 0 .and. &
                         index(res%message, 'C4') > 0 .and. res%t_reached > 0.05_wp .and. res%t_reached < 0.125_wp, &
                         'a joint driven past 90 deg with free RX, RZ: singularity reported clearly', trim(res%message))
    end subroutine test_joint_through_90_singular

    !> The same drive with C4's RX and RZ locked: no singularity, the run
    !! completes and the energy balance closes.
    subroutine test_joint_through_90_locked()
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        character(len=120) :: d
        call run_lines([character(len=80) :: neck, 'PRESCRIB  C4        RY        HARMONIC  120.0     2.0', &
                        'LOCK      C4        RX        RZ'], control(0.2_wp, 1.0e-5_wp, 'DOPRI5', 1.0e-7_wp), res, ch)
        write (d, '(a,i0,a,es9.2,a,es9.2,a)') 'exit ', res%exit_code, ', balance ', res%energy_residual, ' J of ', &
            res%energy_scale, ' J'
        call suite%check(res%exit_code == 0 .and. res%energy_residual < 1.0e-5_wp*res%energy_scale, &
                         'a joint driven past 90 deg with RX, RZ locked: completes, energy closes', d)
    end subroutine test_joint_through_90_locked

    !> The full model at rest under gravity, posture held: no drift. (An
    !! explicit method needs steps within its stability limit even at rest,
    !! so ADAMS is run for 1 s and ROS2, the method for such runs, for 10 s.)
    subroutine test_long_run_at_rest(method, t_end)
        character(len=*), intent(in) :: method
        real(wp), intent(in) :: t_end
        type(run_result_t) :: res
        type(channel_set_t) :: ch
        character(len=80), allocatable :: deck(:)
        integer :: k, ith, iz
        real(wp) :: drift
        character(len=2), parameter :: coords(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']
        character(len=120) :: d
        deck = [character(len=80) :: 'TITLE     54-DOF MODEL AT REST', 'INCLUDE   input/head_neck_54dof.inp', &
                'HOLD      POSTURE', 'OUTPUT    0.01']
        do k = 1, 6
            deck = [character(len=80) :: deck, 'PRESCRIB  T1        '//coords(k)//'        CONSTANT']
        end do
        call run_lines(deck, control(t_end, 1.0e-4_wp, method, 1.0e-6_wp), res, ch)
        ith = findloc(ch%name, 'HEAD_THETY', dim=1)
        iz = findloc(ch%name, 'HEAD_DZ', dim=1)
        ! head rotation [rad] and vertical displacement [m] against 100 atol (atol = rtol/100 = 1e-8)
        drift = max(maxval(abs(res%samples(ith, :)))*deg, maxval(abs(res%samples(iz, :)))/1000)
        write (d, '(a,es9.2,a,es9.2,a,i0,a)') 'largest head rotation or displacement ', drift, &
            ' (rad, m), balance ', res%energy_residual, ' J, ', res%nsteps, ' steps'
        write (d(len_trim(d) + 1:), '(a,f5.1,a)') ' over ', t_end, ' s'
        call suite%check(res%exit_code == 0 .and. drift < 100*1.0e-8_wp .and. res%energy_residual < 1.0e-9_wp, &
                         trim(method)//' at rest under gravity, posture held: no drift', d)
    end subroutine test_long_run_at_rest

end program test_stability
