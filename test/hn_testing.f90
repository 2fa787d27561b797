!> The project's small assertion module. A test program makes one
!! `test_suite_t`, runs one check per test procedure and ends with
!! `call suite%finish()`, which prints "N passed, N failed" and exits
!! non-zero on any failure.
module hn_testing
    use hn_kinds, only: wp
    use iso_fortran_env, only: output_unit, error_unit
    implicit none
    private

    public :: test_suite_t

    !> Counts and reports checks.
    type :: test_suite_t
        integer :: passed = 0
        integer :: failed = 0
    contains
        procedure :: check => suite_check
        procedure :: near => suite_near
        procedure :: finish => suite_finish
    end type test_suite_t

contains

    !> Record one check named `name`; `detail` is printed with the result.
    subroutine suite_check(me, ok, name, detail)
        class(test_suite_t), intent(inout) :: me
        logical, intent(in) :: ok
        character(len=*), intent(in) :: name
        character(len=*), intent(in), optional :: detail
        character(len=:), allocatable :: d
        d = ''
        if (present(detail)) d = '  ['//trim(detail)//']'
        if (ok) then
            me%passed = me%passed + 1
            write (output_unit, '(3a)') 'PASS  ', name, d
        else
            me%failed = me%failed + 1
            write (output_unit, '(3a)') 'FAIL  ', name, d
        end if
        flush (output_unit)
    end subroutine suite_check

    !> Check |actual - expected| <= tol and report the numbers.
    subroutine suite_near(me, actual, expected, tol, name)
        class(test_suite_t), intent(inout) :: me
        real(wp), intent(in) :: actual, expected, tol
        character(len=*), intent(in) :: name
        character(len=160) :: d
        write (d, '(a,es16.9,a,es16.9,a,es9.2,a,es9.2)') 'got ', actual, ' expected ', expected, &
            ' |diff| ', abs(actual - expected), ' tol ', tol
        call me%check(abs(actual - expected) <= tol, name, d)
    end subroutine suite_near

    !> Print the closing line and exit non-zero on any failure.
    subroutine suite_finish(me)
        class(test_suite_t), intent(inout) :: me
        write (output_unit, '(i0,a,i0,a)') me%passed, ' passed, ', me%failed, ' failed'
        flush (output_unit)
        if (me%failed > 0) then
            write (error_unit, '(i0,a)') me%failed, ' check(s) failed'
            error stop 1
        end if
    end subroutine suite_finish

end module hn_testing
