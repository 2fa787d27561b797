!> Bounded and located deck input (issue 14): numbers beyond the double
!! range refused before conversion, limits on tables and lines, devices and
!! directories refused as INCLUDE targets, INCLUDE resolution (next to the
!! including file, include path), errors that name their card, reserved
!! names, no free coordinate, RUNLIMIT, and the new plausibility warnings.
!! The expected values are literals: the numbers as written, the limits as
!! documented in docs/errors.md, the lines where the test put the cards.
module test_deck_limits
    use funit
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_deck_reader, only: parse_real, max_deck_lines
    use hn_posix, only: make_directories, remove_directory
    implicit none

    character(len=*), parameter :: scratch = 'test_deck_limits_scratch.inp'
    character(len=*), parameter :: dir = 'test_deck_limits_dir'

contains

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

    !> A small valid deck: a base locked to R and an arm free to swing.
    function good() result(lines)
        character(len=80), allocatable :: lines(:)
        lines = [character(len=80) :: &
                 'TITLE     DECK LIMITS', &
                 'CONTROL   0.01      1.0E-4    0.005     DOPRI5', &
                 'BODY      BASE      R         2.0       0.1       0.2       0.3', &
                 'BODY      ARM       BASE      1.5       0.01      0.02      0.015', &
                 'LOCK      BASE      TX        TY        TZ        RX        RY        RZ']
    end function good

    subroutine read_lines(lines, cs, stat, msg)
        character(len=*), intent(in) :: lines(:)
        type(case_t), intent(out) :: cs
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        call write_lines(scratch, lines)
        call read_case(scratch, 'stdin', cs, stat, msg)
        call delete_file(scratch)
    end subroutine read_lines

    subroutine assert_refused(lines, needles)
        character(len=*), intent(in) :: lines(:), needles(:)
        type(case_t) :: cs
        integer :: stat, k
        character(len=msglen) :: msg
        call read_lines(lines, cs, stat, msg)
#line 68 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(stat /= 0, 'refused: '//trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 68) )
  if (anyExceptions()) return
#line 69 "/work/main/test/unit/test_deck_limits.pf"
        do k = 1, size(needles)
#line 70 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(index(msg, trim(needles(k))) > 0, 'message names "'//trim(needles(k))//'": '//trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 70) )
  if (anyExceptions()) return
#line 71 "/work/main/test/unit/test_deck_limits.pf"
        end do
    end subroutine assert_refused

    !@test
    subroutine test_numbers_beyond_double_range_refused_before_conversion()
        real(wp) :: v
        logical :: ok
        character(len=10) :: why
        call parse_real('1.0E+400', v, ok, why)
#line 80 "/work/main/test/unit/test_deck_limits.pf"
  call assertFalse(ok, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 80) )
  if (anyExceptions()) return
#line 81 "/work/main/test/unit/test_deck_limits.pf"
#line 81 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual('overflow', trim(why), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 81) )
  if (anyExceptions()) return
#line 82 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('1.0D+999', v, ok, why)
#line 83 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual('overflow', trim(why), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 83) )
  if (anyExceptions()) return
#line 84 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('-1.0E+309', v, ok, why)
#line 85 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual('overflow', trim(why), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 85) )
  if (anyExceptions()) return
#line 86 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('1000.0E306', v, ok, why)
#line 87 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual('overflow', trim(why), '1000.0E306 = 1E309 by its digits', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 87) )
  if (anyExceptions()) return
#line 88 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('1.0E-400', v, ok, why)
#line 89 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual('underflow', trim(why), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 89) )
  if (anyExceptions()) return
#line 90 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('1.79E308', v, ok, why)
#line 91 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(ok, '1.79E308 is below huge', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 91) )
  if (anyExceptions()) return
#line 92 "/work/main/test/unit/test_deck_limits.pf"
#line 92 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(1.79e308_wp, v, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 92) )
  if (anyExceptions()) return
#line 93 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('0.001E311', v, ok, why)
#line 94 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(ok, '0.001E311 = 1E308 by its digits', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 94) )
  if (anyExceptions()) return
#line 95 "/work/main/test/unit/test_deck_limits.pf"
#line 95 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(1.0e308_wp, v, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 95) )
  if (anyExceptions()) return
#line 96 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('4.9E-324', v, ok, why)
#line 97 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(ok, 'the smallest subnormal is representable', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 97) )
  if (anyExceptions()) return
#line 98 "/work/main/test/unit/test_deck_limits.pf"
#line 98 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(v > 0.0_wp, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 98) )
  if (anyExceptions()) return
#line 99 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('1E-0000001', v, ok, why)
#line 100 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(ok, 'leading zeros in an exponent', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 100) )
  if (anyExceptions()) return
#line 101 "/work/main/test/unit/test_deck_limits.pf"
#line 101 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(0.1_wp, v, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 101) )
  if (anyExceptions()) return
#line 102 "/work/main/test/unit/test_deck_limits.pf"
        call parse_real('0.0E+999', v, ok, why)
#line 103 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(ok, 'zero with any exponent is zero', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 103) )
  if (anyExceptions()) return
#line 104 "/work/main/test/unit/test_deck_limits.pf"
#line 104 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(0.0_wp, v, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 104) )
  if (anyExceptions()) return
#line 105 "/work/main/test/unit/test_deck_limits.pf"
    end subroutine test_numbers_beyond_double_range_refused_before_conversion

    !@test
    subroutine test_overflow_in_a_field_is_located()
        character(len=80), allocatable :: d(:)
        d = good()
        d(3) = 'BODY      BASE      R         1.0E+400  0.1       0.2       0.3'
        call assert_refused(d, [character(len=40) :: 'stdin line 3', 'columns 31-40', 'beyond the range'])
    end subroutine test_overflow_in_a_field_is_located

    !@test
    subroutine test_table_point_limit()
        call assert_refused([character(len=80) :: good(), 'TABLE     BIG       100001'], &
                            [character(len=40) :: 'stdin line 6', 'number of points', '[1, 100000]'])
    end subroutine test_table_point_limit

    !@test
    subroutine test_line_limit()
        character(len=3), allocatable :: lines(:)
        allocate (lines(max_deck_lines + 1))
        lines = '* c'
        lines(1) = 'TIT'
        call write_lines(scratch, lines)
        call check_file_refused(scratch, [character(len=40) :: 'line 1000001', 'more than 1000000 lines'])
        call delete_file(scratch)
    end subroutine test_line_limit

    subroutine check_file_refused(fname, needles)
        character(len=*), intent(in) :: fname, needles(:)
        type(case_t) :: cs
        integer :: stat, k
        character(len=msglen) :: msg
        call read_case(fname, 'stdin', cs, stat, msg)
#line 138 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(stat /= 0, 'refused', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 138) )
  if (anyExceptions()) return
#line 139 "/work/main/test/unit/test_deck_limits.pf"
        do k = 1, size(needles)
#line 140 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(index(msg, trim(needles(k))) > 0, 'message names "'//trim(needles(k))//'": '//trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 140) )
  if (anyExceptions()) return
#line 141 "/work/main/test/unit/test_deck_limits.pf"
        end do
    end subroutine check_file_refused

    !@test
    subroutine test_include_of_a_device_refused_at_the_include_line()
        logical :: exists
        inquire (file='/dev/zero', exist=exists)
        if (.not. exists) return       ! no such device on this system
        call assert_refused([character(len=80) :: good(), 'INCLUDE   /dev/zero'], &
                            [character(len=40) :: 'stdin line 6', 'INCLUDE card', 'character device'])
    end subroutine test_include_of_a_device_refused_at_the_include_line

    !@test
    subroutine test_include_of_a_directory_refused_at_the_include_line()
        integer :: st
        character(len=80), allocatable :: g(:)
        g = good()
        call make_directories(dir, st)
#line 159 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(0, st, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 159) )
  if (anyExceptions()) return
#line 160 "/work/main/test/unit/test_deck_limits.pf"
        call assert_refused([character(len=80) :: g(1:2), 'INCLUDE   '//dir, g(3:)], &
                            [character(len=40) :: 'stdin line 3', 'INCLUDE card', 'is a directory'])
        call remove_directory(dir, st)
    end subroutine test_include_of_a_directory_refused_at_the_include_line

    !@test
    subroutine test_include_resolved_next_to_the_including_file()
        type(case_t) :: cs
        integer :: stat, st
        character(len=msglen) :: msg
        character(len=80), allocatable :: g(:)
        g = good()
        call make_directories(dir//'/sub', st)
        ! sub/a.inp includes b.inp, which sits next to it (not in the working directory)
        call write_lines(dir//'/sub/a.inp', [character(len=80) :: 'INCLUDE   b.inp'])
        call write_lines(dir//'/sub/b.inp', [character(len=80) :: g(3:)])
        call read_lines([character(len=80) :: g(1:2), 'INCLUDE   '//dir//'/sub/a.inp'], cs, stat, msg)
#line 177 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 177) )
  if (anyExceptions()) return
#line 178 "/work/main/test/unit/test_deck_limits.pf"
#line 178 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(2, cs%model%tree%nbody, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 178) )
  if (anyExceptions()) return
#line 179 "/work/main/test/unit/test_deck_limits.pf"
#line 179 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(1.5_wp, cs%model%tree%mass(2), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 179) )
  if (anyExceptions()) return
#line 180 "/work/main/test/unit/test_deck_limits.pf"
        call delete_file(dir//'/sub/a.inp')
        call delete_file(dir//'/sub/b.inp')
        call remove_directory(dir//'/sub', st)
        call remove_directory(dir, st)
    end subroutine test_include_resolved_next_to_the_including_file

    !@test
    subroutine test_include_path_and_error_located_through_the_include()
        type(case_t) :: cs
        integer :: stat, st
        character(len=msglen) :: msg
        character(len=80), allocatable :: model(:)
        call make_directories(dir//'/lib', st)
        model = good()
        model(4) = 'BODY      ARM       BASE      -1.5      0.01      0.02      0.015'
        call write_lines(dir//'/lib/onpath.inp', [character(len=80) :: model(3:)])
        call write_lines(scratch, [character(len=80) :: model(1:2), '* a comment', 'INCLUDE   onpath.inp'])
        call read_case(scratch, 'stdin', cs, stat, msg)
#line 198 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(stat /= 0, 'not found without the include path', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 198) )
  if (anyExceptions()) return
#line 199 "/work/main/test/unit/test_deck_limits.pf"
#line 199 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(index(msg, 'stdin line 4') > 0 .and. index(msg, 'not found') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 199) )
  if (anyExceptions()) return
#line 200 "/work/main/test/unit/test_deck_limits.pf"
        call read_case(scratch, 'stdin', cs, stat, msg, [character(len=80) :: dir//'/lib'])
#line 201 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(stat /= 0, 'found on the include path; its mass is refused', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 201) )
  if (anyExceptions()) return
#line 202 "/work/main/test/unit/test_deck_limits.pf"
#line 202 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(index(msg, dir//'/lib/onpath.inp line 2') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 202) )
  if (anyExceptions()) return
#line 203 "/work/main/test/unit/test_deck_limits.pf"
#line 203 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(index(msg, '(included from stdin line 4)') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 203) )
  if (anyExceptions()) return
#line 204 "/work/main/test/unit/test_deck_limits.pf"
#line 204 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(index(msg, 'mass') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 204) )
  if (anyExceptions()) return
#line 205 "/work/main/test/unit/test_deck_limits.pf"
        call delete_file(scratch)
        call delete_file(dir//'/lib/onpath.inp')
        call remove_directory(dir//'/lib', st)
        call remove_directory(dir, st)
    end subroutine test_include_path_and_error_located_through_the_include

    !@test
    subroutine test_two_roots_name_both_body_cards()
        character(len=80), allocatable :: d(:)
        d = good()
        d(4) = 'BODY      ARM       R         1.5       0.01      0.02      0.015'
        call assert_refused(d, [character(len=40) :: 'stdin line 4', 'columns 21-30', 'ARM has parent R', &
                                'BASE (stdin line 3)', '2 bodies have parent R'])
    end subroutine test_two_roots_name_both_body_cards

    !@test
    subroutine test_loop_of_parents_names_a_body_card()
        call assert_refused([character(len=80) :: good(), &
                             'BODY      C         D         1.0       0.01      0.01      0.01', &
                             'BODY      D         C         1.0       0.01      0.01      0.01'], &
                            [character(len=40) :: 'stdin line 6', 'loop of parents', 'C -> D -> C'])
    end subroutine test_loop_of_parents_names_a_body_card

    !@test
    subroutine test_inertia_error_names_body_and_bodypi_cards()
        call assert_refused([character(len=80) :: good(), 'BODYPI    ARM       0.5       0.0       0.0'], &
                            [character(len=40) :: 'stdin line 4 (BODY card ARM', 'BODYPI card is at stdin line 6', &
                             'positive definite'])
    end subroutine test_inertia_error_names_body_and_bodypi_cards

    !@test
    subroutine test_reserved_names_refused_for_their_reason()
        character(len=80), allocatable :: d(:)
        d = good()
        d(4) = 'BODY      ALL       BASE      1.5       0.01      0.02      0.015'
        call assert_refused(d, [character(len=40) :: 'stdin line 4', 'reserved', 'LOCK ALL'])
        d(4) = 'BODY      INERTIAL  BASE      1.5       0.01      0.02      0.015'
        call assert_refused(d, [character(len=40) :: 'stdin line 4', 'inertial frame'])
    end subroutine test_reserved_names_refused_for_their_reason

    !@test
    subroutine test_continuation_card_error_names_its_card()
        call assert_refused([character(len=80) :: good(), 'TABLE     T         4', &
                             '          0.0       0.0       1.0       2.0       2.0       2.0', &
                             '          X         0.0'], &
                            [character(len=40) :: 'stdin line 8', 'columns 11-20', 'TABLE card continuation 2', &
                             "field F1 'time'"])
    end subroutine test_continuation_card_error_names_its_card

    !@test
    subroutine test_no_free_coordinate_refused_at_the_last_lock()
        call assert_refused([character(len=80) :: good(), &
                             'LOCK      ARM       TX        TY        TZ        RX        RY        RZ'], &
                            [character(len=40) :: 'stdin line 6 (LOCK card)', 'no free coordinate'])
        call assert_refused([character(len=80) :: good(), &
                             'LOCK      ARM       TX        TY        TZ        RX        RY', &
                             'PRESCRIB  ARM       RZ        CONSTANT'], &
                            [character(len=40) :: 'stdin line 7 (PRESCRIB card)', '1 active, all prescribed'])
    end subroutine test_no_free_coordinate_refused_at_the_last_lock

    !@test
    subroutine test_runlimit_card()
        type(case_t) :: cs
        integer :: stat
        character(len=msglen) :: msg
        call read_lines([character(len=80) :: good(), 'RUNLIMIT  10.0      500'], cs, stat, msg)
#line 271 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 271) )
  if (anyExceptions()) return
#line 272 "/work/main/test/unit/test_deck_limits.pf"
#line 272 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(10.0_wp, cs%wall_limit, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 272) )
  if (anyExceptions()) return
#line 273 "/work/main/test/unit/test_deck_limits.pf"
#line 273 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(500, cs%step_limit, &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 273) )
  if (anyExceptions()) return
#line 274 "/work/main/test/unit/test_deck_limits.pf"
        call assert_refused([character(len=80) :: good(), 'RUNLIMIT'], &
                            [character(len=40) :: 'stdin line 6', 'RUNLIMIT card', 'found no limit'])
    end subroutine test_runlimit_card

    !@test
    subroutine test_degenerate_masses_and_zero_scales_warned()
        type(case_t) :: cs
        logical :: zero_table
        integer :: stat
        character(len=msglen) :: msg
        character(len=80), allocatable :: d(:)
        d = good()
        d(4) = 'BODY      ARM       BASE      1.0E-6    1.0E-12   1.0E-12   1.0E-12'
        call read_lines([character(len=80) :: d, 'TABLE     Z         2         1.0       4.9E-324', &
                         '          0.0       1600.0    1.0       1600.0'], cs, stat, msg)
#line 289 "/work/main/test/unit/test_deck_limits.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 289) )
  if (anyExceptions()) return
#line 290 "/work/main/test/unit/test_deck_limits.pf"
#line 290 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(any(index(cs%warnings, 'body ARM: mass') > 0), 'light mass warned', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 290) )
  if (anyExceptions()) return
#line 291 "/work/main/test/unit/test_deck_limits.pf"
#line 291 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(any(index(cs%warnings, 'smallest principal inertia') > 0), 'small inertia warned', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 291) )
  if (anyExceptions()) return
#line 292 "/work/main/test/unit/test_deck_limits.pf"
        zero_table = any(index(cs%warnings, 'table Z') > 0 .and. index(cs%warnings, 'zero in effect') > 0)
#line 293 "/work/main/test/unit/test_deck_limits.pf"
  call assertTrue(zero_table, 'zero table warned', &
 & location=SourceLocation( &
 & 'test_deck_limits.pf', &
 & 293) )
  if (anyExceptions()) return
#line 294 "/work/main/test/unit/test_deck_limits.pf"
    end subroutine test_degenerate_masses_and_zero_scales_warned

end module test_deck_limits

module Wraptest_deck_limits
   use FUnit
   use test_deck_limits
   implicit none
   private

contains


end module Wraptest_deck_limits

function test_deck_limits_suite() result(suite)
   use FUnit
   use test_deck_limits
   use Wraptest_deck_limits
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_deck_limits_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_numbers_beyond_double_range_refused_before_conversion', &
      test_numbers_beyond_double_range_refused_before_conversion))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_overflow_in_a_field_is_located', &
      test_overflow_in_a_field_is_located))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_table_point_limit', &
      test_table_point_limit))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_line_limit', &
      test_line_limit))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_include_of_a_device_refused_at_the_include_line', &
      test_include_of_a_device_refused_at_the_include_line))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_include_of_a_directory_refused_at_the_include_line', &
      test_include_of_a_directory_refused_at_the_include_line))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_include_resolved_next_to_the_including_file', &
      test_include_resolved_next_to_the_including_file))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_include_path_and_error_located_through_the_include', &
      test_include_path_and_error_located_through_the_include))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_two_roots_name_both_body_cards', &
      test_two_roots_name_both_body_cards))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_loop_of_parents_names_a_body_card', &
      test_loop_of_parents_names_a_body_card))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_inertia_error_names_body_and_bodypi_cards', &
      test_inertia_error_names_body_and_bodypi_cards))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_reserved_names_refused_for_their_reason', &
      test_reserved_names_refused_for_their_reason))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_continuation_card_error_names_its_card', &
      test_continuation_card_error_names_its_card))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_no_free_coordinate_refused_at_the_last_lock', &
      test_no_free_coordinate_refused_at_the_last_lock))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_runlimit_card', &
      test_runlimit_card))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_degenerate_masses_and_zero_scales_warned', &
      test_degenerate_masses_and_zero_scales_warned))
   call suite%addTest(t)


end function test_deck_limits_suite

