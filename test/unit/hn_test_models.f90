!> Shared fixtures of the tests: the reproducible random generator, random
!! trees and small textbook mechanisms.
module hn_test_models
    use hn_kinds, only: wp, zero, one, msglen
    use hn_rotation, only: axis_angle_matrix
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_random, only: rng_t
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_run, only: run_state_t, run_result_t, exit_deck
    use hn_channels, only: channel_set_t, channels_define
    implicit none
    private

    public :: rng_t, random_tree, random_inertia, pendulum_tree, elliptic_k
    public :: write_lines, delete_file, read_deck_lines, parser_check_deck
    public :: three_body_neck, control_card, run_lines, kept_run_t

    !> The study cards of the shipped NBDL calibration decks (RATING,
    !! CHANNEL and PEAK, with their comment cards; docs/sweeps.md), for the
    !! calibration decks the tests write.
    character(len=80), parameter, public :: nbdl_study_cards(15) = [character(len=80) :: &
        '*         rated window (ms)   CFC class peak-time tolerance (ms)', &
        'RATING    30.0      250.0     60        10.0', &
        '*         channel   from file conversion file of its runs in each DATA directory', &
        'CHANNEL   HEAD_AX   VALUE               Head_XAccel.csv', &
        'CHANNEL   HEAD_AZ   VALUE               Head_ZAccel.csv', &
        'CHANNEL   HEAD_ALPHYVALUE               Head_YrotAccel.csv', &
        'CHANNEL   HEAD_OMEGYRATE      DEG-RAD   Head_YrotDisp.csv', &
        'CHANNEL   HEAD_THETYVALUE               Head_YrotDisp.csv', &
        '*         channel   extreme   window (ms)         name in the listing', &
        'PEAK      HEAD_AX   MIN       30.0      250.0     X-ACCEL', &
        'PEAK      HEAD_AZ   MIN       30.0      125.0     Z-ACCEL DIP', &
        'PEAK      HEAD_AZ   MAX       125.0     250.0     Z-ACCEL REBOUND', &
        'PEAK      HEAD_ALPHYMAX       30.0      250.0     ANG. ACCEL', &
        'PEAK      HEAD_OMEGYMAX       30.0      250.0     ANG. VELOCITY', &
        'PEAK      HEAD_THETYMAX       30.0      250.0     ROTATION']

    !> A run kept for several tests: a suite makes an expensive run once,
    !! the first time a test asks for it (pFUnit has no once-per-suite
    !! fixture), and its tests look at the result.
    type :: kept_run_t
        logical :: done = .false.       !! the run has been made
        type(run_result_t) :: res       !! its result, with every channel at every sample
        type(channel_set_t) :: ch       !! the channels' names
    end type kept_run_t

contains

    !> A small valid deck that uses every kind of card of the deck reader
    !! (the deck-reader tests change one card at a time).
    function parser_check_deck() result(good)
        character(len=80), allocatable :: good(:)
        good = [character(len=80) :: &
                'TITLE     DECK PARSER CHECK', &
                'CONTROL   0.2       1.0E-4    0.01      DOPRI5    1.0E-7    1.0E-9', &
                'GRAVITY   0.0       0.0       -9.81', &
                'BODY      BASE      R         2.0       0.1       0.2       0.3', &
                'BODY      ARM       BASE      1.5       0.01      0.02      0.015', &
                'BODYPI    ARM       0.001     0.0       0.0', &
                'JOINT     ARM       0.0       0.0       0.1       0.0       0.0       -0.05', &
                'LOCK      BASE      TX        TY        TZ        RX        RY        RZ', &
                '* a comment card', &
                'INITIAL   ARM       RY        10.0      20.0', &
                'TABLE     PULSE     4         0.001     9.80665', &
                '          0.0       0.0       1.0       2.0       2.0       2.0', &
                '          3.0       0.0', &
                'PRESCRIB  ARM       TX        ACCEL     PULSE     0.01      0.5', &
                'LIMIT     ARM       RY        -30.0     45.0      0.1       10.0', &
                'SPRING    S1        BASE      ARM       1000.0    5.0', &
                '          0.0       0.0       0.1       0.0       0.0       0.05']
    end function parser_check_deck

    !> A head on a two-joint neck: T1 held, C4, head; discs, ligaments,
    !! muscles, joint dampers; a forehead impact from 2 to 7 ms. No CONTROL
    !! card (see control_card).
    function three_body_neck() result(neck)
        character(len=80), allocatable :: neck(:)
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
    end function three_body_neck

    !> A CONTROL card: end time, step, print interval t_end/10, method,
    !! rtol and atol = rtol/100.
    character(len=80) function control_card(t_end, h, method, rtol) result(c)
        real(wp), intent(in) :: t_end, h, rtol
        character(len=*), intent(in) :: method
        write (c, '(a10,f10.5,es10.2,f10.5,a10,es10.2,es10.2)') 'CONTROL   ', t_end, h, t_end/10, method, rtol, &
            rtol*1.0e-2_wp
    end function control_card

    !> Run a deck given as lines plus a CONTROL card, keeping every channel
    !! at every sample; the listing is discarded. A deck error gives exit
    !! code exit_deck with the message.
    subroutine run_lines(scratch, lines, control, res, ch)
        character(len=*), intent(in) :: scratch, lines(:), control
        type(run_result_t), intent(out) :: res
        type(channel_set_t), intent(out) :: ch
        type(case_t) :: cs
        type(run_state_t) :: run
        character(len=msglen) :: msg
        integer :: u, stat
        call read_deck_lines(scratch, [character(len=max(len(lines), len(control))) :: lines, control], cs, stat, msg)
        if (stat /= 0) then
            res%exit_code = exit_deck
            res%message = msg
            return
        end if
        call channels_define(cs, ch)
        open (newunit=u, file='/dev/null', action='write')
        call run%execute(cs, u, '', res, keep_samples=.true.)
        close (u)
    end subroutine run_lines

    !> Write the lines to file fname, each ended by LF.
    subroutine write_lines(fname, lines)
        character(len=*), intent(in) :: fname, lines(:)
        integer :: u, k
        open (newunit=u, file=fname, status='replace', form='unformatted', access='stream')
        do k = 1, size(lines)
            write (u) trim(lines(k))//achar(10)
        end do
        close (u)
    end subroutine write_lines

    !> Delete file fname if it exists.
    subroutine delete_file(fname)
        character(len=*), intent(in) :: fname
        integer :: u, ios
        open (newunit=u, file=fname, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine delete_file

    !> Read a deck given as lines through the whole deck reader (as if from
    !! standard input), by way of the scratch file `scratch`.
    subroutine read_deck_lines(scratch, lines, cs, stat, msg)
        character(len=*), intent(in) :: lines(:), scratch
        type(case_t), intent(out) :: cs
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        call write_lines(scratch, lines)
        call read_case(scratch, 'stdin', cs, stat, msg)
        call delete_file(scratch)
    end subroutine read_deck_lines

    !> A random centroidal inertia: principal values obeying the triangle
    !! inequality, rotated to random principal axes.
    function random_inertia(rng, scale) result(a)
        type(rng_t), intent(inout) :: rng
        real(wp), intent(in) :: scale
        real(wp) :: a(3, 3), p(3), r(3, 3)
        integer :: i
        p(1) = rng%uniform(0.5_wp, 1.0_wp)
        p(2) = rng%uniform(0.5_wp, 1.0_wp)
        p(3) = rng%uniform(abs(p(1) - p(2)) + 0.1_wp, p(1) + p(2) - 0.05_wp)
        r = axis_angle_matrix([rng%uniform(-2.0_wp, 2.0_wp), rng%uniform(-2.0_wp, 2.0_wp), &
                               rng%uniform(-2.0_wp, 2.0_wp)])
        a = zero
        do i = 1, 3
            a(i, i) = scale*p(i)
        end do
        a = matmul(r, matmul(a, transpose(r)))
        a = 0.5_wp*(a + transpose(a))
    end function random_inertia

    !> A random tree of nb bodies, every coordinate active, with random
    !! parents, masses, inertias and joint offsets.
    subroutine random_tree(tree, nb, rng)
        type(body_tree_t), intent(out) :: tree
        integer, intent(in) :: nb
        type(rng_t), intent(inout) :: rng
        integer :: k, stat
        character(len=msglen) :: msg
        call tree_allocate(tree, nb)
        do k = 1, nb
            if (k == 1) then
                tree%parent(k) = 0
            else
                tree%parent(k) = 1 + int(rng%uniform(zero, one)*(k - 1))
            end if
            tree%mass(k) = rng%uniform(0.3_wp, 4.0_wp)
            tree%inertia(:, :, k) = random_inertia(rng, 0.01_wp)
            tree%joint_parent(:, k) = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), &
                                       rng%uniform(0.0_wp, 0.08_wp)]
            tree%joint_child(:, k) = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), &
                                      rng%uniform(-0.08_wp, 0.0_wp)]
        end do
        call tree_build(tree, stat, msg)
        if (stat /= 0) error stop 'random_tree: '//trim(msg)
    end subroutine random_tree

    !> A chain of nb pendulum links swinging about y: link k has mass m(k),
    !! centroidal inertia about y iyy(k), joint point c(k) above its mass
    !! centre, and the next joint len(k) below its own joint. Only the
    !! rotation about y of each link is active.
    subroutine pendulum_tree(tree, m, iyy, c, len)
        type(body_tree_t), intent(out) :: tree
        real(wp), intent(in) :: m(:), iyy(:), c(:), len(:)
        integer :: k, stat, nb
        character(len=msglen) :: msg
        nb = size(m)
        call tree_allocate(tree, nb)
        do k = 1, nb
            tree%mass(k) = m(k)
            tree%inertia(:, :, k) = zero
            tree%inertia(1, 1, k) = iyy(k)
            tree%inertia(2, 2, k) = iyy(k)
            tree%inertia(3, 3, k) = 0.1_wp*iyy(k)
            tree%joint_child(:, k) = [zero, zero, c(k)]
            if (k > 1) tree%joint_parent(:, k) = [zero, zero, -(len(k - 1) - c(k - 1))]
            tree%active(:, k) = .false.
            tree%active(5, k) = .true.
        end do
        call tree_build(tree, stat, msg)
        if (stat /= 0) error stop 'pendulum_tree: '//trim(msg)
    end subroutine pendulum_tree

    !> Complete elliptic integral of the first kind K(k) by the
    !! arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1-k^2))).
    pure real(wp) function elliptic_k(k) result(kk)
        real(wp), intent(in) :: k
        real(wp) :: a, b, an
        integer :: i
        a = one
        b = sqrt(one - k**2)
        do i = 1, 60
            an = 0.5_wp*(a + b)
            b = sqrt(a*b)
            a = an
            if (abs(a - b) < 1.0e-16_wp*a) exit
        end do
        kk = acos(-one)/(2.0_wp*a)
    end function elliptic_k

end module hn_test_models
