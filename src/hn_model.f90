!> The model: body tree, which coordinates are prescribed and how, gravity,
!! force elements and applied loads. Everything a dynamics evaluation reads.
module hn_model
    use hn_kinds, only: wp, zero, g_std
    use hn_tree, only: body_tree_t
    use hn_motion, only: motion_t
    use hn_line_elements, only: spring_t
    use hn_applied, only: applied_load_t
    use hn_linsolve, only: solver_gauss
    implicit none
    private

    public :: model_t, model_init

    !> A complete mechanical model.
    type :: model_t
        character(len=80) :: title = ''
        type(body_tree_t) :: tree
        real(wp) :: gravity(3) = [zero, zero, -g_std]  !! gravitational acceleration in R [m/s^2]
        logical, allocatable :: prescribed(:)          !! (n) coordinate driven by `motion`
        type(motion_t), allocatable :: motion(:)       !! (n) its time history
        type(spring_t), allocatable :: springs(:)
        type(applied_load_t), allocatable :: applied(:)
        integer :: solver = solver_gauss               !! solver of a_ij xddot = f
    end type model_t

contains

    !> Start a model on a built tree: nothing prescribed, no elements.
    pure subroutine model_init(model, tree)
        type(model_t), intent(out) :: model
        type(body_tree_t), intent(in) :: tree
        model%tree = tree
        allocate (model%prescribed(tree%ndof), model%motion(tree%ndof))
        model%prescribed = .false.
        allocate (model%springs(0), model%applied(0))
    end subroutine model_init

end module hn_model
