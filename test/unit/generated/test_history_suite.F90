!> The history store keeps a fixed amount in memory and spills the rest to
!! a scratch file: every row comes back exactly as it was added.
module test_history
    use funit
    use hn_kinds, only: wp
    use hn_history, only: history_t
    implicit none

contains

    !@test
    subroutine test_rows_beyond_memory_come_back_exactly()
        type(history_t) :: h
        real(wp) :: row(3)
        real(wp), allocatable :: c(:)
        integer :: i
        call h%init(3, bytes=16*3*8)      ! 16 rows in memory, the rest on disk
        do i = 1, 1000
            call h%add([real(i, wp), 1.0_wp/i, -real(i, wp)**2])
        end do
#line 21 "/work/main/test/unit/test_history.pf"
  call assertEqual(1000, h%n, &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 21) )
  if (anyExceptions()) return
#line 22 "/work/main/test/unit/test_history.pf"
#line 22 "/work/main/test/unit/test_history.pf"
  call assertEqual(16, h%cap, &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 22) )
  if (anyExceptions()) return
#line 23 "/work/main/test/unit/test_history.pf"
#line 23 "/work/main/test/unit/test_history.pf"
  call assertEqual(0, h%stat, &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 23) )
  if (anyExceptions()) return
#line 24 "/work/main/test/unit/test_history.pf"
        do i = 1, 1000, 37
            call h%get(i, row)
#line 26 "/work/main/test/unit/test_history.pf"
  call assertEqual([real(i, wp), 1.0_wp/i, -real(i, wp)**2], row, &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 26) )
  if (anyExceptions()) return
#line 27 "/work/main/test/unit/test_history.pf"
        end do
        c = h%column(2)
#line 29 "/work/main/test/unit/test_history.pf"
  call assertEqual(1000, size(c), &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 29) )
  if (anyExceptions()) return
#line 30 "/work/main/test/unit/test_history.pf"
#line 30 "/work/main/test/unit/test_history.pf"
  call assertEqual(1.0_wp/999, c(999), &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 30) )
  if (anyExceptions()) return
#line 31 "/work/main/test/unit/test_history.pf"
#line 31 "/work/main/test/unit/test_history.pf"
  call assertEqual(1.0_wp/17, c(17), &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 31) )
  if (anyExceptions()) return
#line 32 "/work/main/test/unit/test_history.pf"
        call h%clear()
#line 33 "/work/main/test/unit/test_history.pf"
  call assertEqual(0, h%n, &
 & location=SourceLocation( &
 & 'test_history.pf', &
 & 33) )
  if (anyExceptions()) return
#line 34 "/work/main/test/unit/test_history.pf"
    end subroutine test_rows_beyond_memory_come_back_exactly

end module test_history

module Wraptest_history
   use FUnit
   use test_history
   implicit none
   private

contains


end module Wraptest_history

function test_history_suite() result(suite)
   use FUnit
   use test_history
   use Wraptest_history
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_history_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_rows_beyond_memory_come_back_exactly', &
      test_rows_beyond_memory_come_back_exactly))
   call suite%addTest(t)


end function test_history_suite

