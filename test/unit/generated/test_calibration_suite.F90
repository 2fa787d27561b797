!> The calibration machinery (hn_calibrate): Nelder-Mead finds the known
!! minimum of a quadratic in the unit cube, also on a bound; the CORA-style
!! rating of a model equal to the volunteers' mean is 1, and a shifted copy
!! loses exactly the phase rating of its lag; the volunteer peaks read from
!! reference/nbdl_15g equal those of tools/compare_nbdl.py (a second
!! implementation, in Python).
module test_calibration
    use funit
    use hn_kinds, only: wp, zero, one, msglen
    use hn_calibrate, only: nelder_mead, cora_rating, volunteer_t, read_volunteers
    implicit none

contains

    function quadratic(u) result(f)
        real(wp), intent(in) :: u(:)
        real(wp) :: f
        f = (u(1) - 0.3_wp)**2 + 2*(u(2) - 0.7_wp)**2 + (u(3) - 0.55_wp)**2 + 0.1_wp
    end function quadratic

    function corner(u) result(f)
        real(wp), intent(in) :: u(:)
        real(wp) :: f
        f = (u(1) - 1.4_wp)**2 + (u(2) + 0.2_wp)**2
    end function corner

    !@test
    subroutine test_nelder_mead_finds_the_minimum_of_a_quadratic()
        real(wp) :: u(3), f
        integer :: n
        call nelder_mead(quadratic, [0.5_wp, 0.5_wp, 0.5_wp], 0.15_wp, 400, 1.0e-14_wp, u, f, n)
#line 32 "/work/main/test/unit/test_calibration.pf"
  call assertEqual([0.3_wp, 0.7_wp, 0.55_wp], u, 1.0e-4_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 32) )
  if (anyExceptions()) return
#line 33 "/work/main/test/unit/test_calibration.pf"
#line 33 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(0.1_wp, f, 1.0e-8_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 33) )
  if (anyExceptions()) return
#line 34 "/work/main/test/unit/test_calibration.pf"
    end subroutine test_nelder_mead_finds_the_minimum_of_a_quadratic

    !@test
    subroutine test_nelder_mead_stops_on_the_bounds()
        real(wp) :: u(2), f
        integer :: n
        ! the unconstrained minimum (1.4, -0.2) lies outside: the answer is the corner (1, 0)
        call nelder_mead(corner, [0.5_wp, 0.5_wp], 0.15_wp, 400, 1.0e-14_wp, u, f, n)
#line 42 "/work/main/test/unit/test_calibration.pf"
  call assertEqual([one, zero], u, 1.0e-4_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 42) )
  if (anyExceptions()) return
#line 43 "/work/main/test/unit/test_calibration.pf"
    end subroutine test_nelder_mead_stops_on_the_bounds

    !@test
    subroutine test_rating_of_the_mean_and_of_a_lagged_copy()
        real(wp) :: t(601), r(601), s(601), y(601), c, x, rating, lag
        integer :: i
        do i = 1, 601
            t(i) = 0.5_wp*(i - 1)
            r(i) = exp(-((t(i) - 120.0_wp)/25.0_wp)**2)
        end do
        s = 0.1_wp
        call cora_rating(t, r, r, s, c, x, rating, lag)
#line 55 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(one, rating, 1.0e-12_wp, 'the mean itself rates 1', &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 55) )
  if (anyExceptions()) return
#line 56 "/work/main/test/unit/test_calibration.pf"
        ! delayed by 10 ms: best lag -10 ms, phase rating (30 - 10)/28, shape and size 1
        do i = 1, 601
            y(i) = exp(-((t(i) - 130.0_wp)/25.0_wp)**2)
        end do
        call cora_rating(t, y, r, s, c, x, rating, lag)
#line 61 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(-10.0_wp, lag, 1.0e-12_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 61) )
  if (anyExceptions()) return
#line 62 "/work/main/test/unit/test_calibration.pf"
#line 62 "/work/main/test/unit/test_calibration.pf"
  call assertEqual((20.0_wp/28.0_wp + 2.0_wp)/3.0_wp, x, 1.0e-9_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 62) )
  if (anyExceptions()) return
#line 63 "/work/main/test/unit/test_calibration.pf"
    end subroutine test_rating_of_the_mean_and_of_a_lagged_copy

    !@test
    subroutine test_volunteer_peaks_equal_the_python_report()
        type(volunteer_t) :: vd
        integer :: stat
        character(len=msglen) :: msg
        call read_volunteers('reference/nbdl_15g', vd, stat, msg)
#line 71 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(0, stat, msg, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 71) )
  if (anyExceptions()) return
#line 72 "/work/main/test/unit/test_calibration.pf"
#line 72 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(7, vd%nrun, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 72) )
  if (anyExceptions()) return
#line 73 "/work/main/test/unit/test_calibration.pf"
        ! tools/compare_nbdl.py --case 15g: x-acceleration -29.4 +- 4.01 g at 97 +- 2 ms,
        ! angular acceleration 1890 +- 310 rad/s^2, rotation 85.8 +- 5.79 deg
#line 75 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(-29.4_wp, vd%peak_mean(1), 0.05_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 75) )
  if (anyExceptions()) return
#line 76 "/work/main/test/unit/test_calibration.pf"
#line 76 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(4.01_wp, vd%peak_sd(1), 0.005_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 76) )
  if (anyExceptions()) return
#line 77 "/work/main/test/unit/test_calibration.pf"
#line 77 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(1890.0_wp, vd%peak_mean(4), 5.0_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 77) )
  if (anyExceptions()) return
#line 78 "/work/main/test/unit/test_calibration.pf"
#line 78 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(310.0_wp, vd%peak_sd(4), 0.5_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 78) )
  if (anyExceptions()) return
#line 79 "/work/main/test/unit/test_calibration.pf"
#line 79 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(85.8_wp, vd%peak_mean(6), 0.05_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 79) )
  if (anyExceptions()) return
#line 80 "/work/main/test/unit/test_calibration.pf"
#line 80 "/work/main/test/unit/test_calibration.pf"
  call assertEqual(5.79_wp, vd%peak_sd(6), 0.005_wp, &
 & location=SourceLocation( &
 & 'test_calibration.pf', &
 & 80) )
  if (anyExceptions()) return
#line 81 "/work/main/test/unit/test_calibration.pf"
    end subroutine test_volunteer_peaks_equal_the_python_report

end module test_calibration

module Wraptest_calibration
   use FUnit
   use test_calibration
   implicit none
   private

contains


end module Wraptest_calibration

function test_calibration_suite() result(suite)
   use FUnit
   use test_calibration
   use Wraptest_calibration
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_calibration_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_nelder_mead_finds_the_minimum_of_a_quadratic', &
      test_nelder_mead_finds_the_minimum_of_a_quadratic))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_nelder_mead_stops_on_the_bounds', &
      test_nelder_mead_stops_on_the_bounds))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_rating_of_the_mean_and_of_a_lagged_copy', &
      test_rating_of_the_mean_and_of_a_lagged_copy))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_volunteer_peaks_equal_the_python_report', &
      test_volunteer_peaks_equal_the_python_report))
   call suite%addTest(t)


end function test_calibration_suite

