!> Named status codes of the library's procedures (`stat` arguments) and
!! their meanings (the doc comment of each). Index information (which row, body or point)
!! travels in separate arguments, never in `stat`. Program exit codes are
!! separate (hn_run); these are the reasons behind them.
module hn_status
    implicit none
    private

    public :: stat_ok, stat_bad_input, stat_bad_model, stat_bad_table, stat_singular, stat_ill_conditioned, &
              stat_gimbal, stat_not_finite, stat_energy_lost, stat_step_failed, stat_io

    integer, parameter :: stat_ok = 0               !! success
    integer, parameter :: stat_bad_input = 1        !! a deck, card, option or argument is not acceptable
    integer, parameter :: stat_bad_model = 2        !! the body tree or a model reduction is inconsistent
    integer, parameter :: stat_bad_table = 3        !! a table is empty, mis-sized or its times do not increase
    integer, parameter :: stat_singular = 4         !! a matrix (a_ij, an iteration matrix) is singular
    integer, parameter :: stat_ill_conditioned = 5  !! a_ij is too ill-conditioned for the result to be trusted
    integer, parameter :: stat_gimbal = 6           !! Bryant-angle singularity: first and third axes coincide
    integer, parameter :: stat_not_finite = 7       !! the state became NaN or infinite
    integer, parameter :: stat_energy_lost = 8      !! the energy balance was lost (the solution grows)
    integer, parameter :: stat_step_failed = 9      !! the integrator could not take a step
    integer, parameter :: stat_io = 10              !! a file could not be read or written

end module hn_status
