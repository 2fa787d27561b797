!> Deck fuzzing: at least 500 mutated decks generated deterministically from
!! the shipped decks (INCLUDE expanded), each invalid by construction --
!! shifted cards, letters, NaN and Inf in numeric fields, missing and
!! duplicated cards, truncated files, huge, zero and negative values where
!! a positive one is required, unknown cards, references to bodies that do
!! not exist, loops in the tree, non-positive-definite inertia, tabs,
!! non-ASCII bytes, overlong lines, empty input, numbers beyond the double
!! range, devices, FIFOs and directories as INCLUDE targets, tables beyond
!! their point limit, a deck beyond the line limit, every coordinate locked.
!! Every one must be refused with a message that names the line and columns,
!! or the card, body or element concerned, and nothing may crash (in the
!! checking build too, which traps floating-point overflow). CR LF line
!! ends are one mutation a deck survives: such a deck must read exactly as
!! the original; degenerate masses and inertias are the other: accepted,
!! with a warning naming the body.
program test_fuzz
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_model, only: family_count
    use hn_families, only: family_index
    use hn_deck, only: read_case
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t
    use hn_posix, only: remove_file
    implicit none

    type :: line_t
        character(len=:), allocatable :: s
    end type line_t

    type(test_suite_t) :: suite
    type(rng_t) :: rng
    character(len=20), parameter :: decks(5) = [character(len=20) :: 'case6-1', 'case6-2', 'case6-5', 'nbdl15g', &
                                                'hybrid3_flexion']
    character(len=*), parameter :: scratch = 'test_fuzz_scratch.inp'
    integer :: nrefused, ntotal, nbad, ncrlf, ncrlf_ok, k, nper(26), nwarn, nwarn_ok
    character(len=400) :: first_bad
    character(len=24), parameter :: kinds(26) = [character(len=24) :: 'shifted card', 'letters in a number', &
        'NaN or Inf text', 'missing card', 'duplicated card', 'truncated file', 'huge value', 'negative value', &
        'zero value', 'unknown card', 'unknown body', 'loop in the tree', 'non-PD inertia', 'tab character', &
        'non-ASCII byte', 'overlong line', 'empty input', 'orphan continuation', 'bad name', 'limits reversed', &
        'beyond double range', 'device/FIFO/dir INCLUDE', 'table beyond limit', 'deck beyond line limit', &
        'degenerate mass', 'no free coordinate']

    nrefused = 0; ntotal = 0; nbad = 0; ncrlf = 0; ncrlf_ok = 0; nper = 0; nwarn = 0; nwarn_ok = 0
    first_bad = ''
    do k = 1, size(decks)
        call fuzz_deck('input/'//trim(decks(k))//'.inp')
    end do
    call check_mutant([line_t ::], 17)          ! empty input
    call huge_deck()
    call report()
    call suite%finish()

contains

    !> The deck with INCLUDE cards replaced by the included lines.
    recursive function expanded(path) result(lines)
        character(len=*), intent(in) :: path
        type(line_t), allocatable :: lines(:)
        character(len=200) :: buf
        integer :: u, ios
        allocate (lines(0))
        open (newunit=u, file=path, status='old', action='read')
        do
            read (u, '(a)', iostat=ios) buf
            if (ios /= 0) exit
            if (buf(1:8) == 'INCLUDE ') then
                lines = [lines, expanded(trim(adjustl(buf(11:))))]
            else
                lines = [lines, line_t(trim(buf))]
            end if
        end do
        close (u)
    end function expanded

    logical function is_card(l) result(r)
        type(line_t), intent(in) :: l
        r = .false.
        if (len(l%s) == 0) return
        r = l%s(1:1) /= '*' .and. l%s(1:1) /= ' '
    end function is_card

    logical function is_continuation(l) result(r)
        type(line_t), intent(in) :: l
        r = .false.
        if (len(l%s) < 11) return
        r = l%s(1:10) == '' .and. len_trim(l%s) > 10
    end function is_continuation

    function key(l) result(k)
        type(line_t), intent(in) :: l
        character(len=8) :: k
        k = ''
        if (is_card(l)) k = l%s(1:min(8, len(l%s)))
    end function key

    !> Field f of a line (blank if beyond the line).
    function field(l, f) result(s)
        type(line_t), intent(in) :: l
        integer, intent(in) :: f
        character(len=10) :: s
        integer :: c1
        c1 = 1 + 10*f
        s = ''
        if (len(l%s) >= c1) s = l%s(c1:min(len(l%s), c1 + 9))
    end function field

    !> The line with field f replaced by text (right-padded to 10 columns).
    function with_field(l, f, text) result(r)
        type(line_t), intent(in) :: l
        integer, intent(in) :: f
        character(len=*), intent(in) :: text
        type(line_t) :: r
        character(len=80) :: buf
        character(len=10) :: t
        buf = l%s
        t = text
        buf(1 + 10*f:10 + 10*f) = t
        r%s = trim(buf)
    end function with_field

    integer function pick(n) result(i)
        integer, intent(in) :: n
        i = 1 + min(n - 1, int(rng%uniform(0.0_wp, 1.0_wp)*n))
    end function pick

    !> Lines whose card is `k` (main card lines).
    function lines_with_key(lines, k) result(idx)
        type(line_t), intent(in) :: lines(:)
        character(len=*), intent(in) :: k
        integer, allocatable :: idx(:)
        integer :: i
        allocate (idx(0))
        do i = 1, size(lines)
            if (key(lines(i)) == k) idx = [idx, i]
        end do
    end function lines_with_key

    function replaced(lines, i, l) result(out)
        type(line_t), intent(in) :: lines(:), l
        integer, intent(in) :: i
        type(line_t), allocatable :: out(:)
        out = lines
        out(i) = l
    end function replaced

    subroutine fuzz_deck(path)
        character(len=*), intent(in) :: path
        type(line_t), allocatable :: d(:)
        integer, allocatable :: idx(:)
        integer :: rep, i, f, j
        type(line_t) :: l
        character(len=10), parameter :: letters(4) = [character(len=10) :: 'ABC', '1.0X', '1,5', '2..0']
        character(len=10), parameter :: nans(4) = [character(len=10) :: 'NaN', 'Inf', '-Infinity', 'nan']
        character(len=10), parameter :: beyond(4) = [character(len=10) :: '1.0E+400', '1.0D+999', '-1.0E+309', &
                                                     '1.0E-400']
        character(len=40), parameter :: specials(4) = [character(len=40) :: '/dev/zero', '/dev/urandom', 'input', &
                                                       'test_fuzz_fifo']
        d = expanded(path)
        do rep = 1, 6
            ! 1 shift a main card right by 1 to 3 columns
            i = random_card(d)
            call check_mutant(replaced(d, i, line_t(repeat(' ', pick(3))//d(i)%s)), 1)
            ! 2 letters, 3 NaN/Inf in a numeric field
            call numeric_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, letters(pick(4)))), 2)
            call numeric_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, nans(pick(4)))), 3)
            ! 7 huge, 8 negative, 9 zero where a positive value is required
            call positive_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, '1.0E+300')), 7)
            call positive_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, '-1.0')), 8)
            call positive_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, '0.0')), 9)
            ! 10 unknown card type
            i = random_card(d)
            call check_mutant(replaced(d, i, line_t('BODDY   '//d(i)%s(min(9, len(d(i)%s) + 1):))), 10)
            ! 11 a body that does not exist
            call body_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, 'NOBODY')), 11)
            ! 14 tab, 15 non-ASCII, 16 overlong line
            i = pick(size(d))
            j = min(len(d(i)%s) + 1, 1 + pick(70))
            call check_mutant(replaced(d, i, line_t(d(i)%s(1:j - 1)//achar(9)//d(i)%s(j:))), 14)
            i = pick(size(d))
            call check_mutant(replaced(d, i, line_t(d(i)%s//achar(200))), 15)
            i = pick(size(d))
            l%s = d(i)%s//repeat(' ', max(0, 80 - len(d(i)%s)))//'X'
            call check_mutant(replaced(d, i, l), 16)
            ! 18 an orphan continuation card (its main card removed)
            i = card_with_continuation(d)
            call check_mutant([d(1:i - 1), d(i + 1:)], 18)
            ! 19 a name with a blank or a bad character
            call body_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, 'C4 X')), 19)
            ! 6 truncated right after a card that needs continuation cards
            i = card_with_continuation(d)
            call check_mutant(d(1:i), 6)
            ! 21 a number beyond the double range (refused before conversion)
            call numeric_field(d, i, f)
            call check_mutant(replaced(d, i, with_field(d(i), f, beyond(pick(4)))), 21)
        end do
        ! 22 INCLUDE of something that never ends or is not a file, after the TITLE
        idx = lines_with_key(d, 'TITLE   ')
        do j = 1, size(specials)
            if (.not. special_exists(specials(j))) cycle
            call check_mutant([d(1:idx(1)), line_t('INCLUDE   '//trim(specials(j))), d(idx(1) + 1:)], 22)
        end do
        ! 23 a table beyond its point limit
        idx = lines_with_key(d, 'TABLE   ')
        do j = 1, min(size(idx), 2)
            call check_mutant(replaced(d, idx(j), with_field(d(idx(j)), 2, '100001')), 23)
            call check_mutant(replaced(d, idx(j), with_field(d(idx(j)), 2, '999999999')), 23)
        end do
        ! 25 degenerate but valid masses and inertias: accepted with a warning
        idx = lines_with_key(d, 'BODY    ')
        do j = 1, size(idx)
            call check_warned(replaced(d, idx(j), with_field(with_field(with_field(with_field(d(idx(j)), 3, &
                              '1.0E-6'), 4, '1.0E-12'), 5, '1.0E-12'), 6, '1.0E-12')), &
                              'body '//trim(adjustl(field(d(idx(j)), 1)))//': mass')
        end do
        ! 26 every coordinate locked
        call check_mutant([d, line_t('LOCK      ALL       TX        TY        TZ        RX        RY        RZ')], 26)
        ! 4 missing cards: TITLE, CONTROL, every BODY
        idx = lines_with_key(d, 'TITLE   ')
        call check_mutant([d(1:idx(1) - 1), d(idx(1) + 1:)], 4)
        idx = lines_with_key(d, 'CONTROL ')
        call check_mutant([d(1:idx(1) - 1), d(idx(1) + 1:)], 4)
        idx = lines_with_key(d, 'BODY    ')
        do j = 1, size(idx)
            call check_mutant([d(1:idx(j) - 1), d(idx(j) + 1:)], 4)
        end do
        ! 5 duplicated cards that may appear once
        call duplicate(d, 'TITLE   ')
        call duplicate(d, 'CONTROL ')
        call duplicate(d, 'HOLD    ')
        call duplicate(d, 'OUTPUT  ')
        call duplicate(d, 'HEADNECK')
        idx = lines_with_key(d, 'BODY    ')
        do j = 1, size(idx)
            call check_mutant([d(1:idx(j)), d(idx(j):)], 5)
        end do
        idx = lines_with_key(d, 'JOINT   ')
        do j = 1, size(idx)
            call check_mutant([d(1:idx(j)), d(idx(j):)], 5)
        end do
        ! 12 loops: the root hangs from the head; a body from its own child
        idx = lines_with_key(d, 'BODY    ')
        call check_mutant(replaced(d, idx(1), with_field(d(idx(1)), 2, 'HEAD')), 12)
        do j = 2, size(idx) - 1
            call check_mutant(replaced(d, idx(j), with_field(d(idx(j)), 2, trim(field(d(idx(j + 1)), 1)))), 12)
        end do
        ! 13 inertia not positive definite: a huge product of inertia
        do j = 1, size(idx)
            call check_mutant([d, line_t('BODYPI    '//field(d(idx(j)), 1)//'0.5')], 13)
        end do
        ! 20 joint-limit range reversed
        idx = lines_with_key(d, 'LIMIT   ')
        do j = 1, min(size(idx), 10)
            call check_mutant(replaced(d, idx(j), with_field(with_field(d(idx(j)), 3, '10.0'), 4, '-10.0')), 20)
        end do
        ! truncated to the title alone
        idx = lines_with_key(d, 'TITLE   ')
        call check_mutant(d(1:idx(1)), 6)
        ! CR LF line ends: the same deck
        call check_crlf(d)
    end subroutine fuzz_deck

    !> A deck beyond the line limit: refused at the line, not read to the end.
    subroutine huge_deck()
        type(line_t), allocatable :: lines(:)
        integer :: k
        allocate (lines(1000002))
        lines(1) = line_t('TITLE     HUGE')
        do k = 2, size(lines)
            lines(k) = line_t('*')
        end do
        call check_mutant(lines, 24)
    end subroutine huge_deck

    !> /dev/zero and the like when this machine has them; a FIFO made here.
    logical function special_exists(path) result(ok)
        character(len=*), intent(in) :: path
        integer :: st
        inquire (file=trim(path), exist=ok)
        if (ok .or. trim(path) /= 'test_fuzz_fifo') return
        call execute_command_line('mkfifo test_fuzz_fifo 2> /dev/null', exitstat=st)
        inquire (file=trim(path), exist=ok)
    end function special_exists

    !> A valid but degenerate deck: accepted, with a warning that contains `needle`.
    subroutine check_warned(lines, needle)
        type(line_t), intent(in) :: lines(:)
        character(len=*), intent(in) :: needle
        type(case_t) :: cs
        integer :: stat
        character(len=msglen) :: msg
        call write_deck(lines, .false.)
        call read_case(scratch, 'stdin', cs, stat, msg)
        nwarn = nwarn + 1
        nper(25) = nper(25) + 1
        if (stat == 0) then
            if (any(index(cs%warnings, needle) > 0)) nwarn_ok = nwarn_ok + 1
        end if
        if (stat /= 0 .and. len_trim(first_bad) == 0) first_bad = 'degenerate mass refused: '//trim(msg)
    end subroutine check_warned

    subroutine duplicate(d, k)
        type(line_t), intent(in) :: d(:)
        character(len=*), intent(in) :: k
        integer, allocatable :: idx(:)
        idx = lines_with_key(d, k)
        if (size(idx) > 0) call check_mutant([d(1:idx(1)), d(idx(1):)], 5)
    end subroutine duplicate

    integer function random_card(d) result(i)
        type(line_t), intent(in) :: d(:)
        do
            i = pick(size(d))
            if (is_card(d(i))) return
        end do
    end function random_card

    integer function card_with_continuation(d) result(i)
        type(line_t), intent(in) :: d(:)
        do
            i = pick(size(d) - 1)
            if (is_card(d(i)) .and. is_continuation(d(i + 1))) return
        end do
    end function card_with_continuation

    !> A field holding a number (of a main or continuation card).
    subroutine numeric_field(d, i, f)
        type(line_t), intent(in) :: d(:)
        integer, intent(out) :: i, f
        real(wp) :: v
        integer :: ios
        character(len=10) :: txt
        do
            i = pick(size(d))
            if (.not. (is_card(d(i)) .or. is_continuation(d(i)))) cycle
            if (key(d(i)) == 'TITLE   ' .or. key(d(i)) == 'H5FILE  ') cycle
            f = pick(7)
            if (len_trim(field(d(i), f)) == 0) cycle
            txt = field(d(i), f)
            read (txt, *, iostat=ios) v
            if (ios == 0 .and. verify(trim(adjustl(txt)), '0123456789.+-E') == 0) return
        end do
    end subroutine numeric_field

    !> A field that must hold a positive value.
    subroutine positive_field(d, i, f)
        type(line_t), intent(in) :: d(:)
        integer, intent(out) :: i, f
        do
            i = random_card(d)
            select case (key(d(i)))
            case ('BODY    '); f = 2 + pick(4)            ! mass, inertias
            case ('CONTROL '); f = pick(3)                ! end time, step, print interval
            case ('DISC    '); f = 3 + pick(3)            ! area, thickness, modulus
            case ('OUTPUT  '); f = 1
            case default; cycle
            end select
            return
        end do
    end subroutine positive_field

    !> A field naming a body.
    subroutine body_field(d, i, f)
        type(line_t), intent(in) :: d(:)
        integer, intent(out) :: i, f
        do
            i = random_card(d)
            select case (key(d(i)))
            case ('JOINT   ', 'PRESCRIB', 'LIMIT   ', 'FORCE   '); f = 1
            case ('DISC    ', 'LIGAMENT', 'MUSCLE  '); f = 1 + pick(2)
            case ('BODY    ')
                f = 2
                if (field(d(i), 2) == 'R') cycle
            case default; cycle
            end select
            return
        end do
    end subroutine body_field

    !> Write the lines to the scratch deck (LF or CR LF line ends).
    subroutine write_deck(lines, crlf)
        type(line_t), intent(in) :: lines(:)
        logical, intent(in) :: crlf
        integer :: u, i
        open (newunit=u, file=scratch, status='replace', form='unformatted', access='stream')
        do i = 1, size(lines)
            if (crlf) then
                write (u) lines(i)%s//achar(13)//achar(10)
            else
                write (u) lines(i)%s//achar(10)
            end if
        end do
        close (u)
    end subroutine write_deck

    !> The mutant must be refused with a located or named message.
    subroutine check_mutant(lines, kind)
        type(line_t), intent(in) :: lines(:)
        integer, intent(in) :: kind
        type(case_t) :: cs
        integer :: stat
        character(len=msglen) :: msg
        logical :: named
        call write_deck(lines, .false.)
        call read_case(scratch, 'stdin', cs, stat, msg)
        ntotal = ntotal + 1
        nper(kind) = nper(kind) + 1
        named = (index(msg, ' line ') > 0 .and. index(msg, 'column') > 0) .or. index(msg, 'body ') > 0 .or. &
                index(msg, 'the deck has no ') > 0 .or. index(msg, 'the deck is empty') > 0 .or. &
                (index(msg, ' line ') > 0 .and. index(msg, ' card') > 0) .or. &
                (index(msg, ' line ') > 0 .and. index(msg, 'the limit on a deck') > 0)
        if (stat /= 0 .and. named) then
            nrefused = nrefused + 1
        else
            nbad = nbad + 1
            if (len_trim(first_bad) == 0) write (first_bad, '(a,a,a,i0,2a)') trim(kinds(kind)), ': ', &
                'stat ', stat, ', message: ', trim(msg)
        end if
    end subroutine check_mutant

    !> CR LF line ends read as the same deck.
    subroutine check_crlf(d)
        type(line_t), intent(in) :: d(:)
        type(case_t) :: a, b
        integer :: sa, sb
        character(len=msglen) :: ma, mb
        call write_deck(d, .false.)
        call read_case(scratch, 'stdin', a, sa, ma)
        call write_deck(d, .true.)
        call read_case(scratch, 'stdin', b, sb, mb)
        ncrlf = ncrlf + 1
        if (sa == 0 .and. sb == 0 .and. size(a%deck) == size(b%deck)) then
            if (a%model%tree%ndof == b%model%tree%ndof .and. all(abs(a%x0 - b%x0) <= 0.0_wp) .and. &
                abs(a%t_end - b%t_end) <= 0.0_wp .and. &
                family_count(a%model, family_index('LIGAMENTS')) == &
                family_count(b%model, family_index('LIGAMENTS'))) &
                ncrlf_ok = ncrlf_ok + 1
        end if
    end subroutine check_crlf

    subroutine report()
        integer :: u, k
        character(len=200) :: d
        open (newunit=u, file=scratch, status='old')
        close (u, status='delete')
        call remove_file('test_fuzz_fifo', k)          ! a FIFO: unlinked, never opened
        do k = 1, size(kinds)
            write (*, '(a,a24,i5)') '      ', kinds(k), nper(k)
        end do
        write (d, '(i0,a,i0,a,i0,a)') nrefused, ' of ', ntotal, ' mutated decks refused with a located message; ', &
            nbad, ' not'
        call suite%check(ntotal >= 500 .and. nbad == 0, 'deck fuzzing: every mutated deck refused clearly, none crashed', &
                         trim(d)//' '//trim(first_bad))
        write (d, '(i0,a,i0)') ncrlf_ok, ' of ', ncrlf
        call suite%check(ncrlf_ok == ncrlf, 'CR LF line ends: every deck reads as with LF line ends', d)
        write (d, '(i0,a,i0)') nwarn_ok, ' of ', nwarn
        call suite%check(nwarn_ok == nwarn .and. nwarn > 0, 'degenerate masses and inertias: accepted, '// &
                         'with a warning naming the body', d)
    end subroutine report

end program test_fuzz
