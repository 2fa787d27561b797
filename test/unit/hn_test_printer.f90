!> The printer of the pFUnit test programs (the drivers tools/pfunit.sh
!! generates): one line `PASS  name` or `FAIL  name` per test, each failure
!! followed by its assertion's location and message, as the shell checks
!! print theirs. The driver ends the output with `N passed, N failed`.
module hn_test_printer
    use PF_AbstractPrinter, only: AbstractPrinter
    use PF_AbstractTestResult, only: AbstractTestResult
    use PF_ExceptionList, only: ExceptionList
    use PF_Exception, only: Exception
    implicit none
    private

    public :: line_printer_t

    !> Prints each test's outcome as it ends.
    type, extends(AbstractPrinter) :: line_printer_t
        integer :: unit = 6   !! output unit
    contains
        procedure :: addFailure => printer_failure
        procedure :: addError => printer_error
        procedure :: addSuccess => printer_success
        procedure :: startTest => printer_silent
        procedure :: endTest => printer_silent
        procedure :: print => printer_summary
    end type line_printer_t

contains

    !> `PASS  name`.
    subroutine printer_success(this, testName)
        class(line_printer_t), intent(inout) :: this
        character(len=*), intent(in) :: testName   !! the test's full name
        write (this%unit, '(2a)') 'PASS  ', plain_name(testName)
        flush (this%unit)
    end subroutine printer_success

    !> The test's name with the parameter's label once: pFUnit 4.14 gives
    !! the names of parameterized tests as `name[label][label]`.
    function plain_name(name) result(s)
        character(len=*), intent(in) :: name
        character(len=:), allocatable :: s
        integer :: p, n
        s = name
        p = index(name, '[', back=.true.)
        n = len(name) - p + 1
        if (p > n) then
            if (name(p:) == name(p - n:p - 1)) s = name(:p - 1)
        end if
    end function plain_name

    !> `FAIL  name`, then where and why.
    subroutine printer_failure(this, testName, exceptions)
        class(line_printer_t), intent(inout) :: this
        character(len=*), intent(in) :: testName       !! the test's full name
        type(ExceptionList), intent(in) :: exceptions  !! the failed assertions
        call report(this%unit, 'FAIL  ', testName, exceptions)
    end subroutine printer_failure

    !> An error (a crash caught by pFUnit) counts as a failure.
    subroutine printer_error(this, testName, exceptions)
        class(line_printer_t), intent(inout) :: this
        character(len=*), intent(in) :: testName       !! the test's full name
        type(ExceptionList), intent(in) :: exceptions  !! what went wrong
        call report(this%unit, 'FAIL  ', testName//' (error)', exceptions)
    end subroutine printer_error

    subroutine report(unit, tag, testName, exceptions)
        integer, intent(in) :: unit
        character(len=*), intent(in) :: tag, testName
        type(ExceptionList), intent(in) :: exceptions
        class(Exception), pointer :: e
        integer :: i
        write (unit, '(2a)') tag, plain_name(testName)
        do i = 1, exceptions%size()
            e => exceptions%at(i)
            write (unit, '(2a)') '      at ', trim(e%location%toString())
            write (unit, '(2a)') '      ', e%getMessage()
        end do
        flush (unit)
    end subroutine report

    !> Nothing at a test's start or end.
    subroutine printer_silent(this, testName)
        class(line_printer_t), intent(inout) :: this
        character(len=*), intent(in) :: testName   !! the test's full name
    end subroutine printer_silent

    !> No summary here: the driver prints `N passed, N failed`.
    subroutine printer_summary(this, result, elapsed_time)
        class(line_printer_t), intent(in) :: this
        class(AbstractTestResult), intent(in) :: result  !! the whole run's result
        real, intent(in) :: elapsed_time                 !! seconds
    end subroutine printer_summary

end module hn_test_printer
