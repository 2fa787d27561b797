!> SIGINT and SIGTERM caught so that an interrupted run ends like a stopped
!! one: the loop sees the flag at its next step, writes what it has, marks
!! the result incomplete and exits with code 5. The flag is the one piece of
!! module state in the code: a signal handler receives no context.
module hn_signals
    use, intrinsic :: iso_c_binding, only: c_int, c_funptr, c_funloc
    implicit none
    private

    public :: catch_signals, signal_received

    integer(c_int), parameter :: sigint = 2, sigterm = 15
    integer(c_int), volatile, save :: received = 0

    interface
        function c_signal(signum, handler) bind(C, name='signal') result(old)
            import :: c_int, c_funptr
            integer(c_int), value :: signum
            type(c_funptr), value :: handler
            type(c_funptr) :: old
        end function c_signal
    end interface

contains

    !> Install the handler for SIGINT and SIGTERM.
    subroutine catch_signals()
        type(c_funptr) :: old
        old = c_signal(sigint, c_funloc(on_signal))
        old = c_signal(sigterm, c_funloc(on_signal))
    end subroutine catch_signals

    subroutine on_signal(signum) bind(C)
        integer(c_int), value :: signum
        received = signum
    end subroutine on_signal

    !> The signal number received so far, 0 if none.
    integer function signal_received()
        signal_received = received
    end function signal_received

end module hn_signals
