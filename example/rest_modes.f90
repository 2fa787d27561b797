!> Eigenvalues of a deck's model at its start state (posture held when the
!! deck says HOLD POSTURE): the largest real parts, each with the free
!! coordinate that dominates its mode. The rest state is stable when every
!! real part is negative (hn_rest_modes).
!!
!!   fpm run --example rest_modes -- DECK [N]     (N eigenvalues printed, default 12)
program rest_modes_example
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_tree, only: dof_label
    use hn_rest_modes, only: rest_mode_t, rest_modes
    implicit none
    character(len=512) :: deck, arg
    type(case_t) :: cs
    type(rest_mode_t), allocatable :: modes(:)
    character(len=msglen) :: msg
    integer :: stat, k, nshow
    if (command_argument_count() < 1) error stop 'usage: rest_modes DECK [N]'
    call get_command_argument(1, deck)
    nshow = 12
    if (command_argument_count() >= 2) then
        call get_command_argument(2, arg)
        read (arg, *) nshow
    end if
    call read_case(trim(deck), trim(deck), cs, stat, msg)
    if (stat /= 0) error stop trim(msg)
    call rest_modes(cs%model, cs%t_start, cs%x0, cs%xd0, cs%hold_posture, modes, stat, msg)
    if (stat /= 0) error stop trim(msg)
    write (*, '(a,i0,a)') 'eigenvalues of the start state (', size(modes), '), largest real parts first:'
    write (*, '(a)') '    real (1/s)      imag (1/s)   dominant coordinate'
    do k = 1, min(nshow, size(modes))
        write (*, '(2es16.6,3x,a)') modes(k)%re, modes(k)%im, trim(dof_label(cs%model%tree, modes(k)%dominant))
    end do
    write (*, '(a,i0)') 'eigenvalues with a positive real part: ', count(modes%re > 0)
end program rest_modes_example
