!> The channel table: every channel of every shipped case deck has a unique
!! name and a unit, is found by its name, and the table holds one channel
!! per joint rotation, disc resultant, ligament, muscle and limit damper.
module test_channels
    use funit
    use hn_kinds, only: msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_channels, only: channel_set_t, channels_define, channel_index
    use hn_line_elements, only: muscle_hill
    implicit none

    character(len=*), parameter :: decks(5) = [character(len=32) :: 'input/case6-1.inp', 'input/case6-2.inp', &
                                                'input/case6-5.inp', 'input/nbdl15g.inp', 'input/hybrid3_flexion.inp']

contains

    subroutine load(deck, cs, ch)
        character(len=*), intent(in) :: deck
        type(case_t), intent(out) :: cs
        type(channel_set_t), intent(out) :: ch
        integer :: stat
        character(len=msglen) :: msg
        call read_case(trim(deck), trim(deck), cs, stat, msg)
#line 25 "/work/main/test/unit/test_channels.pf"
  call assertEqual(0, stat, trim(deck)//': '//trim(msg), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 25) )
  if (anyExceptions()) return
#line 26 "/work/main/test/unit/test_channels.pf"
        call channels_define(cs, ch)
    end subroutine load

    !@test
    subroutine test_every_channel_has_a_unit()
        type(case_t) :: cs
        type(channel_set_t) :: ch
        integer :: d, k
        do d = 1, size(decks)
            call load(decks(d), cs, ch)
            if (anyExceptions()) return
            do k = 1, ch%n
#line 38 "/work/main/test/unit/test_channels.pf"
  call assertTrue(len_trim(ch%units(k)) > 0, trim(decks(d))//': channel '//trim(ch%name(k))//' has no unit', &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 38) )
  if (anyExceptions()) return
#line 39 "/work/main/test/unit/test_channels.pf"
            end do
        end do
    end subroutine test_every_channel_has_a_unit

    !@test
    subroutine test_channel_names_are_unique()
        type(case_t) :: cs
        type(channel_set_t) :: ch
        integer :: d, k
        do d = 1, size(decks)
            call load(decks(d), cs, ch)
            if (anyExceptions()) return
            do k = 1, ch%n
#line 52 "/work/main/test/unit/test_channels.pf"
  call assertTrue(len_trim(ch%name(k)) > 0, trim(decks(d))//': a channel has no name', &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 52) )
  if (anyExceptions()) return
#line 53 "/work/main/test/unit/test_channels.pf"
#line 53 "/work/main/test/unit/test_channels.pf"
  call assertEqual(1, count(ch%name == ch%name(k)), trim(decks(d))//': '//trim(ch%name(k))//' repeats', &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 53) )
  if (anyExceptions()) return
#line 54 "/work/main/test/unit/test_channels.pf"
            end do
        end do
    end subroutine test_channel_names_are_unique

    !@test
    subroutine test_channels_found_by_name()
        type(case_t) :: cs
        type(channel_set_t) :: ch
        integer :: k
        call load(decks(4), cs, ch)
        if (anyExceptions()) return
        do k = 1, ch%n
#line 66 "/work/main/test/unit/test_channels.pf"
  call assertEqual(k, channel_index(ch, trim(ch%name(k))), trim(ch%name(k)), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 66) )
  if (anyExceptions()) return
#line 67 "/work/main/test/unit/test_channels.pf"
        end do
#line 68 "/work/main/test/unit/test_channels.pf"
  call assertEqual(0, channel_index(ch, 'NO_SUCH_CHANNEL'), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 68) )
  if (anyExceptions()) return
#line 69 "/work/main/test/unit/test_channels.pf"
    end subroutine test_channels_found_by_name

    !@test
    subroutine test_one_channel_per_joint_and_element()
        type(case_t) :: cs
        type(channel_set_t) :: ch
        integer :: d, nfixed, nenergy, expected
        nfixed = 27      ! head 17, T1 4, occipital condyle 6
        nenergy = 9
        do d = 1, size(decks)
            call load(decks(d), cs, ch)
            if (anyExceptions()) return
            expected = nfixed + 3*(cs%model%tree%nbody - 1) + 3*size(cs%model%discs) + size(cs%model%ligaments) + &
                       size(cs%model%muscles) + count(cs%model%muscles%law == muscle_hill) + &
                       size(cs%model%limits) + nenergy
#line 84 "/work/main/test/unit/test_channels.pf"
  call assertEqual(expected, ch%n, trim(decks(d)), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 84) )
  if (anyExceptions()) return
#line 85 "/work/main/test/unit/test_channels.pf"
#line 85 "/work/main/test/unit/test_channels.pf"
  call assertEqual(ch%n, size(ch%value), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 85) )
  if (anyExceptions()) return
#line 86 "/work/main/test/unit/test_channels.pf"
        end do
    end subroutine test_one_channel_per_joint_and_element

    !@test
    subroutine test_units_of_named_channels()
        type(case_t) :: cs
        type(channel_set_t) :: ch
        call load(decks(4), cs, ch)
        if (anyExceptions()) return
#line 95 "/work/main/test/unit/test_channels.pf"
  call assertEqual('g', trim(ch%units(channel_index(ch, 'HEAD_AX'))), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 95) )
  if (anyExceptions()) return
#line 96 "/work/main/test/unit/test_channels.pf"
#line 96 "/work/main/test/unit/test_channels.pf"
  call assertEqual('rad/s^2', trim(ch%units(channel_index(ch, 'HEAD_ALPHY'))), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 96) )
  if (anyExceptions()) return
#line 97 "/work/main/test/unit/test_channels.pf"
#line 97 "/work/main/test/unit/test_channels.pf"
  call assertEqual('deg', trim(ch%units(channel_index(ch, 'HEAD_THETY'))), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 97) )
  if (anyExceptions()) return
#line 98 "/work/main/test/unit/test_channels.pf"
#line 98 "/work/main/test/unit/test_channels.pf"
  call assertEqual('N m', trim(ch%units(channel_index(ch, 'OC_MY'))), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 98) )
  if (anyExceptions()) return
#line 99 "/work/main/test/unit/test_channels.pf"
#line 99 "/work/main/test/unit/test_channels.pf"
  call assertEqual('J', trim(ch%units(channel_index(ch, 'E_BALANCE'))), &
 & location=SourceLocation( &
 & 'test_channels.pf', &
 & 99) )
  if (anyExceptions()) return
#line 100 "/work/main/test/unit/test_channels.pf"
    end subroutine test_units_of_named_channels

end module test_channels

module Wraptest_channels
   use FUnit
   use test_channels
   implicit none
   private

contains


end module Wraptest_channels

function test_channels_suite() result(suite)
   use FUnit
   use test_channels
   use Wraptest_channels
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_channels_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_every_channel_has_a_unit', &
      test_every_channel_has_a_unit))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_channel_names_are_unique', &
      test_channel_names_are_unique))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_channels_found_by_name', &
      test_channels_found_by_name))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_one_channel_per_joint_and_element', &
      test_one_channel_per_joint_and_element))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_units_of_named_channels', &
      test_units_of_named_channels))
   call suite%addTest(t)


end function test_channels_suite

