!> The line-element families' shared part: elements that pull along a path
!! of attachment points on the bodies (springs, ligaments, muscles;
!! hn_line_elements), each with its own tension law T(L, L', t). A family
!! extending `line_family_t` gives each element's path (`path`), its law
!! (`line_tension`) and the word that names an element in warnings
!! (`line_kind`); this type supplies from them
!! - the tangent: K += (dT/dL) b b^T, C += (dT/dL') b b^T with b = dL/dxdot
!!   the path's row (line_columns) and the law's slopes by central
!!   differences (fd_rel, fd_abs_length, fd_abs_rate of hn_element_family);
!! - the plausibility checks of the attachment points (check_point), to
!!   which a family adds its law's (`law_plausibility`);
!! - the result table's names, bodies and end points (`line_table`).
module hn_line_family
    use hn_kinds, only: wp
    use hn_kinematics, only: kinematics_t
    use hn_tree, only: body_tree_t
    use hn_line_elements, only: max_via
    use hn_element_family, only: element_family_t, tangent_work_t, element_table_t, warning_len, fd_rel, &
                                 fd_abs_length, fd_abs_rate, check_point, line_columns, add_line_tangent
    implicit none
    private

    public :: line_family_t, line_table

    !> A family of line elements: paths and a tension law per element.
    type, abstract, extends(element_family_t) :: line_family_t
    contains
        procedure(path_sub), deferred :: path
        procedure(tension_fn), deferred :: line_tension
        procedure(kind_fn), deferred :: line_kind
        procedure :: add_tangent => line_tangent
        procedure :: plausibility => line_plausibility
        procedure :: law_plausibility => no_law_plausibility
    end type line_family_t

    abstract interface
        !> Element e's name and path: its points in order from end a to end b.
        pure subroutine path_sub(this, e, name, bodies, points, npt)
            import :: line_family_t, wp, max_via
            class(line_family_t), intent(in) :: this          !! the family
            integer, intent(in) :: e                          !! element number
            character(len=12), intent(out) :: name            !! its name
            integer, intent(out) :: bodies(max_via + 2)       !! the points' bodies (0 = inertial frame)
            real(wp), intent(out) :: points(3, max_via + 2)   !! their body-frame positions from the mass centre [m]
            integer, intent(out) :: npt                       !! number of points (2 for a straight element)
        end subroutine path_sub

        !> Element e's tension [N] at path length L, its rate L' and time t.
        pure real(wp) function tension_fn(this, e, t, length, rate) result(tension)
            import :: line_family_t, wp
            class(line_family_t), intent(in) :: this   !! the family
            integer, intent(in) :: e                   !! element number
            real(wp), intent(in) :: t                  !! time [s] (a muscle's activation)
            real(wp), intent(in) :: length             !! path length [m]
            real(wp), intent(in) :: rate               !! its rate [m/s]
        end function tension_fn

        !> The word naming one element in warnings ('spring', 'ligament', ...).
        pure function kind_fn(this) result(word)
            import :: line_family_t
            class(line_family_t), intent(in) :: this   !! the family
            character(len=:), allocatable :: word
        end function kind_fn
    end interface

contains

    !> K += (dT/dL) b b^T, C += (dT/dL') b b^T of every element along its path.
    pure subroutine line_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(line_family_t), intent(in) :: this      !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        type(kinematics_t), intent(in) :: kin         !! kinematics: joint columns filled
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(in) :: xd(:)                 !! their rates
        real(wp), intent(inout) :: kgen(:, :)         !! generalized stiffness, the family's added
        real(wp), intent(inout) :: cgen(:, :)         !! generalized damping, the family's added
        type(tangent_work_t), intent(inout) :: tw     !! scratch sized for the coordinates
        integer :: e, bodies(max_via + 2), npt
        real(wp) :: points(3, max_via + 2), length, rate, dl, dr, kl, cl
        character(len=12) :: name
        logical :: ok
        do e = 1, this%count()
            call this%path(e, name, bodies, points, npt)
            call line_columns(tree, kin, bodies, points, npt, tw%cols, tw%sgn, tw%b, length, rate, ok)
            if (.not. ok) cycle
            dl = max(fd_rel*length, fd_abs_length)
            dr = max(fd_rel*abs(rate), fd_abs_rate)
            kl = (this%line_tension(e, t, length + dl, rate) - this%line_tension(e, t, length - dl, rate))/(2*dl)
            cl = (this%line_tension(e, t, length, rate + dr) - this%line_tension(e, t, length, rate - dr))/(2*dr)
            call add_line_tangent(tw%b, kl, cl, kgen, cgen, tw%idx)
        end do
    end subroutine line_tangent

    !> Attachment points far outside their bodies, and what the family's law adds.
    pure subroutine line_plausibility(this, tree, warnings)
        class(line_family_t), intent(in) :: this      !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the family's added
        integer :: e, bodies(max_via + 2), npt
        real(wp) :: points(3, max_via + 2)
        character(len=12) :: name
        do e = 1, this%count()
            call this%path(e, name, bodies, points, npt)
            call check_point(tree, bodies(1), points(:, 1), this%line_kind()//' '//name, warnings)
            call check_point(tree, bodies(npt), points(:, npt), this%line_kind()//' '//name, warnings)
            call this%law_plausibility(e, warnings)
        end do
    end subroutine line_plausibility

    !> No checks of the law (a family with reference values overrides this).
    pure subroutine no_law_plausibility(this, e, warnings)
        class(line_family_t), intent(in) :: this      !! the family
        integer, intent(in) :: e                      !! element number
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings (unchanged)
    end subroutine no_law_plausibility

    !> The result table of a line family: group, description, and each
    !! element's name, end bodies and end points (a family adds its extra datasets).
    pure function line_table(fam, group, description) result(tab)
        class(line_family_t), intent(in) :: fam       !! the family
        character(len=*), intent(in) :: group         !! its group below /model/elements
        character(len=*), intent(in) :: description   !! what one element is
        type(element_table_t) :: tab
        integer :: e, n, bodies(max_via + 2), npt
        real(wp) :: points(3, max_via + 2)
        n = fam%count()
        tab%group = group
        tab%description = description
        allocate (tab%name(n), tab%body(2, n), tab%point(3, 2, n), tab%extra(0))
        do e = 1, n
            call fam%path(e, tab%name(e), bodies, points, npt)
            tab%body(:, e) = [bodies(1), bodies(npt)]
            tab%point(:, 1, e) = points(:, 1)
            tab%point(:, 2, e) = points(:, npt)
        end do
    end function line_table

end module hn_line_family
