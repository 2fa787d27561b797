!> The STATICS card (docs/deck-format.md): the run is a sequence of static
!! equilibria instead of a time integration (hn_statics). Each level is a
!! load time: the applied tables (FORCE, COUPLE), the prescribed
!! coordinates and the activations are taken at that time, every rate is
!! zero, and the free coordinates are solved for equilibrium.
!!
!!   STATICS   F1 first     the first level's load time [s]
!!             F2 last      the last level's load time [s] (>= first)
!!             F3 step      the step between levels [s] (> 0); the levels
!!                          are first, first + step, ... up to last (last
!!                          included when it is a whole number of steps)
module hn_statics_card
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    implicit none
    private

    public :: statics_card

    integer, parameter :: max_levels = 1000000   !! most levels a card may ask for
    real(wp), parameter :: time_max = 1.0e6_wp   !! largest load time accepted [s]

contains

    !> The STATICS card on line i into cs%statics_times; a bad field is a
    !! located error (rd%fail).
    subroutine statics_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i                  !! the card's line
        type(case_t), intent(inout) :: cs         !! the run case: statics_times set
        real(wp) :: first, last, step, span
        integer :: n, k
        call rd%real(i, 1, 'first load time', 's', first, -time_max, time_max)
        call rd%real(i, 2, 'last load time', 's', last, first, time_max)
        call rd%real(i, 3, 'step between levels', 's', step, 1.0e-9_wp, time_max)
        if (rd%failed()) return
        span = last - first
        ! a last level within 1e-9 steps of a whole number of steps counts as one
        n = floor(span/step + 1.0e-9_wp)
        if (real(n, wp) + 1 > max_levels) then
            call rd%fail(rd%context(i, 3, 'step between levels')//': found "'//trim(rd%raw(i, 3))// &
                         '", which makes more than 1000000 levels; expected a larger step')
            return
        end if
        cs%statics_times = [(first + k*step, k=0, n)]
        if (n > 0) cs%statics_times(n + 1) = min(cs%statics_times(n + 1), last)
    end subroutine statics_card

end module hn_statics_card
