!> Typed views of a model's element families for the tests: copies of
!! each family's elements (`elements_of`), and a model's springs set from
!! a list (`set_springs`).
module hn_test_families
    use hn_model, only: model_t, model_set_family
    use hn_families, only: family_index
    use hn_discs, only: disc_t
    use hn_line_elements, only: ligament_t, muscle_t, spring_t
    use hn_joint_limits, only: joint_limit_t, joint_range_t
    use hn_disc_family, only: discs_of
    use hn_ligament_family, only: ligaments_of
    use hn_muscle_family, only: muscles_of
    use hn_limit_family, only: limits_of, ranges_of
    use hn_spring_family, only: spring_family_t, springs_of
    implicit none
    private

    public :: element_view_t, elements_of, set_springs

    !> Copies of the elements of every family of a model.
    type :: element_view_t
        type(disc_t), allocatable :: discs(:)
        type(ligament_t), allocatable :: ligaments(:)
        type(muscle_t), allocatable :: muscles(:)
        type(joint_limit_t), allocatable :: limits(:)
        type(joint_range_t), allocatable :: ranges(:)
        type(spring_t), allocatable :: springs(:)
    end type element_view_t

contains

    !> The elements of every family of `model`, copied.
    pure function elements_of(model) result(v)
        type(model_t), intent(in) :: model   !! the model
        type(element_view_t) :: v
        v%discs = discs_of(model%family(family_index('DISCS'))%f)
        v%ligaments = ligaments_of(model%family(family_index('LIGAMENTS'))%f)
        v%muscles = muscles_of(model%family(family_index('MUSCLES'))%f)
        v%limits = limits_of(model%family(family_index('LIMITS'))%f)
        v%ranges = ranges_of(model%family(family_index('LIMITS'))%f)
        v%springs = springs_of(model%family(family_index('SPRINGS'))%f)
    end function elements_of

    !> The model's springs become `springs`.
    pure subroutine set_springs(model, springs)
        type(model_t), intent(inout) :: model      !! the model; out: its SPRINGS family holds `springs`
        type(spring_t), intent(in) :: springs(:)   !! the springs
        type(spring_t), allocatable :: s(:)
        ! an allocated copy: a zero-size actual (a constructor [spring_t ::])
        ! would give a component that the model's copy leaves unallocated
        allocate (s(size(springs)))
        s = springs
        call model_set_family(model, family_index('SPRINGS'), spring_family_t(items=s))
    end subroutine set_springs

end module hn_test_families
