!> The deck reader: a valid deck lands in the right places, and every kind
!! of bad card is refused with a message naming line, columns, card, what
!! was found and what was expected.
program test_deck
    use hn_kinds, only: wp, deg, msglen, g_std
    use hn_case, only: case_t
    use hn_motion, only: motion_eval
    use hn_testing, only: test_suite_t
    use hn_test_models, only: read_deck_lines
    implicit none
    character(len=*), parameter :: scratch = 'test_deck_scratch.inp'

    type(test_suite_t) :: suite
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

    call test_valid_deck()
    call test_plausibility_warnings()
    call expect_error('empty deck', [character(len=80) :: ''], [character(len=60) :: 'empty'])
    call expect_error('first card must be TITLE', [character(len=80) :: good(2)], &
                          [character(len=60) :: 'line 1', 'expected a TITLE card first'])
    call expect_error('negative mass', replace(good, 4, &
                          'BODY      BASE      R         -2.0      0.1       0.2       0.3'), &
                      [character(len=60) :: 'stdin line 4', 'columns 31-40', 'BODY card', 'mass', &
                                            'found -2.0'])
    call expect_error('letter in a numeric field', replace(good, 5, &
                          'BODY      ARM       BASE      1.5       0.O1      0.02      0.015'), &
                      [character(len=60) :: 'stdin line 5', 'columns 41-50', 'found "0.O1"', &
                                            'expected a real number'])
    call expect_error('NaN text', replace(good, 3, 'GRAVITY   0.0       NaN       -9.81'), &
                      [character(len=60) :: 'line 3', 'columns 21-30', 'found "NaN"'])
    call expect_error('unknown card', replace(good, 3, 'GRAVTY    0.0       0.0       -9.81'), &
                      [character(len=60) :: 'line 3', 'columns 1-8', 'unknown card "GRAVTY"'])
    call expect_error('missing CONTROL card', drop(good, 2), [character(len=60) :: 'no CONTROL card'])
    call expect_error('second TITLE card', replace(good, 3, 'TITLE     AGAIN'), &
                          [character(len=60) :: 'line 3', 'second TITLE'])
    call expect_error('parent body that does not exist', &
                      replace(good, 5, 'BODY      ARM       NOPE      1.5       0.01      0.02      0.015'), &
                      [character(len=60) :: 'line 5', 'columns 21-30', 'found "NOPE"', 'expected R'])
    call expect_error('a loop of parents', [character(len=80) :: good(1:5), &
                      'BODY      C         D         1.0       0.01      0.01      0.01', &
                      'BODY      D         C         1.0       0.01      0.01      0.01'], &
                                            [character(len=60) :: 'loop of parents'])
    call expect_error('no root body', replace(good, 4, &
                          'BODY      BASE      ARM       2.0       0.1       0.2       0.3'), &
                      [character(len=60) :: '0 bodies have parent R'])
    call expect_error('tab character', replace(good, 3, 'GRAVITY'//achar(9)//'0.0'), &
                          [character(len=60) :: 'line 3', 'column 8', 'tab'])
    call expect_error('carriage return inside a card', &
                      replace(good, 3, 'GRAVITY   0.0'//achar(13)//'      0.0       -9.81'), &
                      [character(len=60) :: 'line 3', 'column 14', 'carriage return'])
    call test_crlf_accepted()
    call expect_error('text beyond column 80', long_line(), &
                          [character(len=60) :: 'line 3', 'beyond column 80'])
    call expect_error('end time before start', &
                      replace(good, 2, &
                                            'CONTROL   0.2       1.0E-4    0.01      RK4                           0.5'), &
                      [character(len=60) :: 'line 2', 'columns 11-20', &
                                            'expected an end time after the start time'])
    call expect_error('zero step', replace(good, 2, 'CONTROL   0.2       0.0       0.01      RK4'), &
                      [character(len=60) :: 'line 2', 'columns 21-30', 'step'])
    call expect_error('tiny step', replace(good, 2, 'CONTROL   0.2       1.0E-13   0.01      RK4'), &
                      [character(len=60) :: 'line 2', 'columns 21-30', 'found 1.0E-13', 'expected a value in'])
    call expect_error('a step needing more than 1E8 steps', replace(good, 2, 'CONTROL   2000.0    1.0E-9    0.01      RK4'), &
                      [character(len=60) :: 'line 2', 'columns 21-30', 'more than 1E8 steps'])
    call expect_error('huge step', replace(good, 2, 'CONTROL   0.2       5.0       0.01      RK4'), &
                      [character(len=60) :: 'line 2', 'columns 21-30', 'no longer than the run'])
    call expect_error('zero print interval', replace(good, 2, 'CONTROL   0.2       1.0E-4    0.0       RK4'), &
                      [character(len=60) :: 'line 2', 'columns 31-40', 'print interval', 'found 0.0'])
    call expect_error('unknown integrator', replace(good, 2, &
                          'CONTROL   0.2       1.0E-4    0.01      EULER'), &
                      [character(len=60) :: 'line 2', 'columns 41-50', 'found "EULER"', 'expected one of'])
    call expect_error('missing continuation card', good(1:12), &
                          [character(len=60) :: 'line 11', 'ends before its 2 continuation'])
    call expect_error('inertia not positive definite', replace(good, 6, &
                          'BODYPI    ARM       0.5       0.0       0.0'), &
                      [character(len=60) :: 'ARM', 'not symmetric positive definite'])
    call expect_error('table times not increasing', &
                      replace(good, 12, '          0.0       0.0       1.0       2.0       1.0       2.0'), &
                      [character(len=60) :: 'line 12', 'point 3', 'times must increase'])
    call expect_error('unknown table', replace(good, 14, &
                          'PRESCRIB  ARM       TX        ACCEL     PULS      0.01      0.5'), &
                      [character(len=60) :: 'line 14', 'columns 41-50', 'found "PULS"', 'TABLE'])
    call expect_error('prescribing a locked coordinate', &
                      replace(good, 14, 'PRESCRIB  BASE      TX        ACCEL     PULSE     0.01      0.5'), &
                      [character(len=60) :: 'line 14', 'BASE.TX is locked'])
    call expect_error('upper limit below lower limit', &
                      replace(good, 15, 'LIMIT     ARM       RY        30.0      -45.0     0.1       10.0'), &
                      [character(len=60) :: 'line 15', 'columns 41-50', 'above the lower limit'])
    call expect_error('INCLUDE of a missing file', replace(good, 3, 'INCLUDE   input/no_such_file.inp'), &
                      [character(len=60) :: 'line 3', 'not found'])
    call expect_error('data beyond the last table point', &
                      replace(good, 13, '          3.0       0.0       4.0       1.0'), &
                      [character(len=60) :: 'line 13', 'after the last of 4 points'])
    call suite%finish()

contains

    function replace(lines, k, text) result(out)
        character(len=80), intent(in) :: lines(:)
        integer, intent(in) :: k
        character(len=*), intent(in) :: text
        character(len=90), allocatable :: out(:)
        out = lines
        out(k) = text
    end function replace

    function drop(lines, k) result(out)
        character(len=80), intent(in) :: lines(:)
        integer, intent(in) :: k
        character(len=80), allocatable :: out(:)
        out = [lines(1:k - 1), lines(k + 1:)]
    end function drop

    function long_line() result(out)
        character(len=90), allocatable :: out(:)
        out = good
        out(3) = 'GRAVITY   0.0       0.0       -9.81                                         0.0 12'
    end function long_line

    subroutine expect_error(name, lines, needles)
        character(len=*), intent(in) :: name
        character(len=*), intent(in) :: lines(:)
        character(len=*), intent(in) :: needles(:)
        type(case_t) :: cs
        integer :: stat, k
        character(len=msglen) :: msg
        logical :: ok
        call read_deck_lines(scratch, lines, cs, stat, msg)
        ok = stat /= 0
        do k = 1, size(needles)
            ok = ok .and. index(msg, trim(needles(k))) > 0
        end do
        call suite%check(ok, 'refused: '//name, trim(msg))
    end subroutine expect_error

    !> CR LF line ends read as LF line ends: the deck means the same.
    subroutine test_crlf_accepted()
        type(case_t) :: a, b
        integer :: s1, s2, k
        character(len=msglen) :: m1, m2
        character(len=81), allocatable :: crlf(:)
        allocate (crlf(size(good)))
        do k = 1, size(good)
            crlf(k) = trim(good(k))//achar(13)
        end do
        call read_deck_lines(scratch, good, a, s1, m1)
        call read_deck_lines(scratch, crlf, b, s2, m2)
        call suite%check(s1 == 0 .and. s2 == 0 .and. size(a%deck) == size(b%deck) .and. &
                         a%model%tree%mass(2) == b%model%tree%mass(2) .and. a%t_end == b%t_end, &
                         'a deck with CR LF line ends reads as the same deck', trim(m2))
    end subroutine test_crlf_accepted

    !> A valid deck with implausible numbers runs, with one warning each:
    !! triangle inequality, an attachment 2 m away, a muscle 1e4 times stiff.
    subroutine test_plausibility_warnings()
        type(case_t) :: cs
        integer :: stat
        character(len=msglen) :: msg
        character(len=80), allocatable :: deck(:)
        logical :: tri, far, stiff
        integer :: k
        deck = replace(good, 4, 'BODY      BASE      R         2.0       0.1       0.1       0.5')
        deck = [character(len=80) :: deck, &
                'SPRING    S2        BASE      ARM       100.0', &
                '          8.0       0.0       0.0       0.0       0.0       0.0', &
                'MUSCLE    M1        BASE      ARM       3.0E7     400.0', &
                '          0.0       0.0       0.0       0.0       0.0       0.0']
        call read_deck_lines(scratch, deck, cs, stat, msg)
        tri = .false.; far = .false.; stiff = .false.
        if (stat == 0) then
            do k = 1, size(cs%warnings)
                tri = tri .or. index(cs%warnings(k), 'triangle inequality') > 0
                far = far .or. index(cs%warnings(k), 'far outside') > 0
                stiff = stiff .or. index(cs%warnings(k), 'orders of magnitude') > 0
            end do
        end if
        call suite%check(stat == 0 .and. tri .and. far .and. stiff, &
                         'implausible but valid numbers give warnings, not errors', trim(msg))
    end subroutine test_plausibility_warnings

    subroutine test_valid_deck()
        type(case_t) :: cs
        integer :: stat
        character(len=msglen) :: msg
        real(wp) :: x, xd, xdd
        logical :: ok
        call read_deck_lines(scratch, good, cs, stat, msg)
        if (stat /= 0) then
            call suite%check(.false., 'valid deck is read', trim(msg)); return
        end if
        associate (m => cs%model, t => cs%model%tree)
            call motion_eval(m%motion(1), 0.0015_wp, x, xd, xdd)
            ok = cs%t_end == 0.2_wp .and. cs%h == 1.0e-4_wp .and. cs%integrator == 'DOPRI5' .and. &
                 cs%rtol == 1.0e-7_wp .and. m%gravity(3) == -9.81_wp .and. t%nbody == 2 .and. t%ndof == 6 .and. &
                 t%mass(2) == 1.5_wp .and. t%inertia(1, 2, 2) == 0.001_wp .and. t%joint_parent(3, 2) == 0.1_wp .and. &
                 t%joint_child(3, 2) == -0.05_wp .and. abs(cs%x0(5) - 10*deg) < 1.0e-15_wp .and. &
                 abs(cs%xd0(5) - 20*deg) < 1.0e-15_wp .and. m%prescribed(1) .and. &
                 abs(xdd - 2*g_std) < 1.0e-12_wp .and. abs(m%limits(1)%xmax - 45*deg) < 1.0e-15_wp .and. &
                 m%limits(1)%dof == 5 .and. abs(m%springs(1)%length0 - 0.1_wp) < 1.0e-15_wp
        end associate
        call suite%check(ok, 'valid deck: every value lands where the card says, in SI units')
    end subroutine test_valid_deck

end program test_deck
