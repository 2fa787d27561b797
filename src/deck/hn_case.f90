!> A run case: the model plus everything the deck says about running it
!! (time span, step, integrator, output requests) and the deck text itself.
module hn_case
    use hn_kinds, only: wp, zero
    use hn_model, only: model_t
    use hn_deck_reader, only: deck_line_t, path_len
    use hn_sections, only: section_t
    use hn_integrators, only: jacobian_steps_default, factor_band_default
    implicit none
    private

    public :: case_t, deck_line_t, path_len

    !> Everything needed to run and report one case.
    type :: case_t
        type(model_t) :: model
        real(wp) :: t_start = zero      !! [s]
        real(wp) :: t_end = zero        !! [s]
        real(wp) :: h = zero            !! fixed step, or first step of adaptive methods [s]
        real(wp) :: print_dt = zero     !! listing interval [s]
        real(wp) :: sample_dt = zero    !! HDF5 sampling interval [s]
        !> accelerations at output times: 'SOLVE' (articulated-body solve at
        !! the interpolated state) or 'HERMITE' (derivative of the cubic
        !! Hermite interpolant of the step's end points, no solve)
        character(len=8) :: output_xdd = 'SOLVE'
        character(len=8) :: integrator = 'RK4'
        real(wp) :: rtol = 1.0e-6_wp, atol = 1.0e-8_wp
        integer :: jac_steps = jacobian_steps_default   !! SOLVER F3: accepted steps one ROS34PW2 Jacobian serves
        real(wp) :: jac_band = factor_band_default      !! SOLVER F4: step-size band of one ROS34PW2 factorization
        real(wp), allocatable :: x0(:), xd0(:)      !! initial active coordinates and rates
        logical :: hold_posture = .false.           !! generalized forces hold the start posture (released: model%hold_release)
        logical :: hold_prestrain = .false.         !! HOLD PRESTRAIN: the joints' elements pre-strained to settle it (hn_prestrain)
        character(len=120) :: hold_where = ''       !! the HOLD card's deck line (messages of a run's start)
        character(len=200) :: hold_note = ''        !! the pre-strain found at the run's start (listing)
        character(len=8) :: events = 'TIME'         !! NONE, TIME (table breakpoints) or STATE (also one-way switches)
        integer :: head = 0                         !! body reported as the head
        integer :: t1 = 0                           !! body reported as T1 (NIC, relative motion)
        character(len=4) :: occupant = 'H50M'       !! CRITERIA: occupant whose Nij intercepts and neck reference values apply
        character(len=8) :: nic_frame = 'INERTIAL'  !! CRITERIA: NIC's x-accelerations, INERTIAL (global x) or HEAD (head x axis)
        type(section_t), allocatable :: loadcells(:)  !! LOADCELL cards: the sections whose loads are channels
        character(len=10), allocatable :: print_groups(:)  !! PRINT cards: their keywords (none: the main groups; hn_print_card)
        character(len=path_len) :: h5file = ''      !! HDF5 result file ('' = none)
        logical :: h5file_included = .false.        !! the H5FILE card is an INCLUDEd deck's (a variant's file is its own)
        character(len=path_len) :: deck_file = ''   !! the deck's file name without directories ('stdin'), in the result file
        real(wp) :: wall_limit = zero               !! RUNLIMIT: stop after this wall time [s] (0 = none)
        integer :: step_limit = 0                   !! RUNLIMIT: stop after this many steps (0 = none)
        character(len=400) :: control_at = ''       !! where the CONTROL card's step is, for messages
        integer :: progress = 0                     !! progress on stderr: 0 off, 1 on a terminal, 2 always (hn_progress)
        real(wp), allocatable :: dump_times(:)      !! times of the cross-checking dump
        real(wp), allocatable :: statics_times(:)   !! STATICS card: the load times of the equilibria (unallocated: a dynamic run)
        type(deck_line_t), allocatable :: deck(:)   !! the cards as read
        character(len=100), allocatable :: scene(:)  !! what the scene cards did (listing summary)
        character(len=160), allocatable :: warnings(:)  !! physical plausibility warnings
        character(len=160), allocatable :: changes(:)   !! what the CHANGE cards did (listing, result file)
        character(len=80), allocatable :: subtitles(:)  !! titles of INCLUDEd case decks, in deck order (listing header)
    end type case_t

end module hn_case
