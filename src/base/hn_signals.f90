!> SIGINT and SIGTERM caught so that an interrupted run ends like a stopped
!! one: the loop sees the flag at its next step, writes what it has, marks
!! the result incomplete and exits with code 5. Before the run has files to
!! close (while the deck is read and checked) a signal ends the program at
!! once, with a message and the same exit code. The flag and the mode are
!! the module's only state: a signal handler receives no context.
module hn_signals
    use, intrinsic :: iso_c_binding, only: c_int, c_funptr, c_funloc
    use hn_posix, only: raw_write_stderr, exit_now
    implicit none
    private

    public :: catch_signals, defer_signals, signal_received

    integer(c_int), parameter :: sigint = 2, sigterm = 15
    integer(c_int), volatile, save :: received = 0
    integer, volatile, save :: exit_code = -1   !! >= 0: a signal ends the program at once with it

    interface
        function c_signal(signum, handler) bind(C, name='signal') result(old)
            import :: c_int, c_funptr
            integer(c_int), value :: signum
            type(c_funptr), value :: handler
            type(c_funptr) :: old
        end function c_signal
    end interface

contains

    !> Install the handler for SIGINT and SIGTERM. With `exit_at_once`, a
    !! signal ends the program immediately with that exit code (until
    !! defer_signals is called); without it, the signal is only recorded.
    subroutine catch_signals(exit_at_once)
        integer, intent(in), optional :: exit_at_once   !! exit code for a signal before the run
        type(c_funptr) :: old
        exit_code = -1
        if (present(exit_at_once)) exit_code = exit_at_once
        old = c_signal(sigint, c_funloc(on_signal))
        old = c_signal(sigterm, c_funloc(on_signal))
    end subroutine catch_signals

    !> From now on a signal is only recorded; the run loop stops at its next step.
    subroutine defer_signals()
        exit_code = -1
    end subroutine defer_signals

    subroutine on_signal(signum) bind(C)
        integer(c_int), value :: signum
        character(len=2) :: num
        received = signum
        if (exit_code >= 0) then
            ! no Fortran I/O in a handler: digits by hand, raw write, _exit
            num = achar(48 + mod(signum/10, 10))//achar(48 + mod(signum, 10))
            if (signum < 10) num = achar(48 + signum)//' '
            call raw_write_stderr('hhneck: interrupted by signal '//trim(num)// &
                                  ' before the run started; nothing was written'//achar(10))
            call exit_now(exit_code)
        end if
    end subroutine on_signal

    !> The signal number received so far, 0 if none.
    integer function signal_received()
        signal_received = received
    end function signal_received

end module hn_signals
