!> Run limits: a step limit stops the run with a message that says where
!! it stands; without limits nothing stops it.
module test_progress
    use funit
    use hn_kinds, only: wp, msglen
    use hn_progress, only: progress_t, progress_off
    implicit none

contains

    !@test
    subroutine test_step_limit_stops_with_where_the_run_stands()
        type(progress_t) :: p
        integer :: stat, k
        character(len=msglen) :: msg
        call p%start(0.0_wp, 0.25_wp, progress_off, 0.0_wp, 10)
        do k = 1, 9
            call p%update(1.0e-3_wp*k, 1.0e-3_wp, k, stat, msg)
#line 19 "/work/main/test/unit/test_progress.pf"
  call assertEqual(0, stat, 'below the limit', &
 & location=SourceLocation( &
 & 'test_progress.pf', &
 & 19) )
  if (anyExceptions()) return
#line 20 "/work/main/test/unit/test_progress.pf"
        end do
        call p%update(0.0123_wp, 2.5e-7_wp, 10, stat, msg)
#line 22 "/work/main/test/unit/test_progress.pf"
  call assertTrue(stat /= 0, 'the limit is reached at step 10', &
 & location=SourceLocation( &
 & 'test_progress.pf', &
 & 22) )
  if (anyExceptions()) return
#line 23 "/work/main/test/unit/test_progress.pf"
#line 23 "/work/main/test/unit/test_progress.pf"
  call assertTrue(index(msg, 'the step limit of 10 steps') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_progress.pf', &
 & 23) )
  if (anyExceptions()) return
#line 24 "/work/main/test/unit/test_progress.pf"
#line 24 "/work/main/test/unit/test_progress.pf"
  call assertTrue(index(msg, 'at t = 1.2300E-02 s of 0.2500 s') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_progress.pf', &
 & 24) )
  if (anyExceptions()) return
#line 25 "/work/main/test/unit/test_progress.pf"
#line 25 "/work/main/test/unit/test_progress.pf"
  call assertTrue(index(msg, '10 steps (last step 2.50E-07 s)') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_progress.pf', &
 & 25) )
  if (anyExceptions()) return
#line 26 "/work/main/test/unit/test_progress.pf"
    end subroutine test_step_limit_stops_with_where_the_run_stands

    !@test
    subroutine test_no_limit_never_stops()
        type(progress_t) :: p
        integer :: stat
        character(len=msglen) :: msg
        call p%start(0.0_wp, 1.0_wp, progress_off, 0.0_wp, 0)
        call p%update(0.5_wp, 1.0e-3_wp, 2000000000, stat, msg)
#line 35 "/work/main/test/unit/test_progress.pf"
  call assertEqual(0, stat, &
 & location=SourceLocation( &
 & 'test_progress.pf', &
 & 35) )
  if (anyExceptions()) return
#line 36 "/work/main/test/unit/test_progress.pf"
    end subroutine test_no_limit_never_stops

end module test_progress

module Wraptest_progress
   use FUnit
   use test_progress
   implicit none
   private

contains


end module Wraptest_progress

function test_progress_suite() result(suite)
   use FUnit
   use test_progress
   use Wraptest_progress
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_progress_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_step_limit_stops_with_where_the_run_stands', &
      test_step_limit_stops_with_where_the_run_stands))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_no_limit_never_stops', &
      test_no_limit_never_stops))
   call suite%addTest(t)


end function test_progress_suite

