!> Section loads (load cells): the force and moment that the rest of the
!! system exerts on the subtree of one body -- through its joint with the
!! parent (the fixture, R, for the root body), and through every element
!! with one end in the subtree and the other outside it -- about a point,
!! from the Newton-Euler balance of the subtree:
!!
!!   F = sum_k (m_k a_k - m_k g) - F_applied
!!   M_P = sum_k (I_k alpha_k + w_k x I_k w_k + (r_k - P) x (m_k a_k - m_k g)) - M_applied,P
!!
!! over the bodies k of the subtree, where F_applied and M_applied,P are the
!! applied force and couple tables on those bodies (external loads, not
!! loads through the section), and the loads of the clamps (the CLAMPS
!! family: a fixture's support, not a load through the specimen). The
!! occipital-condyle loads are the section of the head at its joint point
!! (hn_channels), a LOADCELL card any other.
module hn_sections
    use hn_kinds, only: wp, zero
    use hn_model, only: model_t
    use hn_tree, only: body_tree_t
    use hn_kinematics, only: kinematics_t
    use hn_applied, only: applied_vector, applied_couple
    use hn_rotation, only: cross
    use hn_clamp_family, only: clamp_family_t, clamp_load
    implicit none
    private

    public :: section_t, subtree_of, section_point, section_load

    integer, parameter, public :: section_name_len = 7   !! longest load-cell name (channel names of 11 characters)

    !> A section: its name, the body whose subtree it cuts off, the body
    !! whose axes it reports in (the cell's mounting) and the point its
    !! moment is taken about.
    type :: section_t
        character(len=section_name_len) :: name = ''
        integer :: body = 0                !! the body (its subtree is the part above the section)
        integer :: frame = 0               !! the body whose axes give the point and the components
        logical :: at_joint = .true.       !! the point is the body's joint point (else `point`)
        real(wp) :: point(3) = zero        !! the point in the frame body's axes from its mass centre [m]
    end type section_t

contains

    !> Whether each body of the tree is `body` or one of its descendants.
    pure function subtree_of(tree, body) result(inside)
        type(body_tree_t), intent(in) :: tree   !! the body tree
        integer, intent(in) :: body             !! the body at the base of the subtree
        logical :: inside(tree%nbody)
        integer :: k, p
        do k = 1, tree%nbody
            p = k
            do while (p /= 0 .and. p /= body)
                p = tree%parent(p)
            end do
            inside(k) = p == body
        end do
    end function subtree_of

    !> The section's point in R [m].
    pure function section_point(kin, sec) result(p)
        type(kinematics_t), intent(in) :: kin   !! kinematics of the tree
        type(section_t), intent(in) :: sec      !! the section
        real(wp) :: p(3)
        if (sec%at_joint) then
            p = kin%joint(:, sec%body)
        else
            p = kin%r(:, sec%frame) + matmul(kin%s(:, :, sec%frame), sec%point)
        end if
    end function section_point

    !> The load the rest of the system exerts on the subtree of `body`:
    !! force and moment about `point`, in R, by the subtree's Newton-Euler
    !! balance at time t.
    pure subroutine section_load(model, kin, acc, alpha, t, body, point, force, moment)
        type(model_t), intent(in) :: model        !! the model: tree, gravity, applied loads
        type(kinematics_t), intent(in) :: kin     !! kinematics at t
        real(wp), intent(in) :: acc(:, :)         !! (3, nb) mass-centre accelerations in R [m/s^2]
        real(wp), intent(in) :: alpha(:, :)       !! (3, nb) angular accelerations in R [rad/s^2]
        real(wp), intent(in) :: t                 !! time [s] (of the applied tables)
        integer, intent(in) :: body               !! the body at the base of the subtree
        real(wp), intent(in) :: point(3)          !! the moment's point in R [m]
        real(wp), intent(out) :: force(3)         !! force on the subtree in R [N]
        real(wp), intent(out) :: moment(3)        !! moment on the subtree about `point` in R [N m]
        logical :: inside(model%tree%nbody)
        real(wp) :: f(3), v(3), iw(3)
        integer :: k, e, fam
        inside = subtree_of(model%tree, body)
        force = zero
        moment = zero
        do k = 1, model%tree%nbody
            if (.not. inside(k)) cycle
            f = model%tree%mass(k)*(acc(:, k) - model%gravity)
            iw = matmul(kin%inertia_r(:, :, k), kin%omega(:, k))
            force = force + f
            moment = moment + matmul(kin%inertia_r(:, :, k), alpha(:, k)) + cross(kin%omega(:, k), iw) &
                     + cross(kin%r(:, k) - point, f)
        end do
        do e = 1, size(model%applied)
            k = model%applied(e)%body
            if (k < 1) cycle
            if (.not. inside(k)) cycle
            v = applied_vector(model%applied(e), kin, t)
            if (model%applied(e)%kind == applied_couple) then
                moment = moment - v
            else
                force = force - v
                moment = moment - cross(kin%r(:, k) + matmul(kin%s(:, :, k), model%applied(e)%point) - point, v)
            end if
        end do
        do fam = 1, size(model%family)
            if (.not. model%family_on(fam)) cycle
            select type (clamps => model%family(fam)%f)
            type is (clamp_family_t)
                call less_clamps(clamps, kin, t, inside, point, force, moment)
            end select
        end do
    end subroutine section_load

    !> A section's load less the clamps' loads on the subtree: each clamp's
    !! load on its body when the body is inside, its reaction on the rig when
    !! the rig is (nothing when both or neither are).
    pure subroutine less_clamps(clamps, kin, t, inside, point, force, moment)
        type(clamp_family_t), intent(in) :: clamps   !! the clamps
        type(kinematics_t), intent(in) :: kin        !! kinematics at t
        real(wp), intent(in) :: t                    !! time [s]
        logical, intent(in) :: inside(:)             !! the subtree's bodies
        real(wp), intent(in) :: point(3)             !! the moment's point in R [m]
        real(wp), intent(inout) :: force(3)          !! the section's force in R [N]
        real(wp), intent(inout) :: moment(3)         !! the section's moment about point in R [N m]
        real(wp) :: p(3), fc(3), mc(3), d(3), phi(3), angle, rel(6), p_rig, sgn
        integer :: e
        do e = 1, size(clamps%items)
            associate (c => clamps%items(e))
                sgn = merge(1.0_wp, zero, inside(c%body))
                if (c%rig > 0) sgn = sgn - merge(1.0_wp, zero, inside(c%rig))
                if (sgn == zero) cycle
                call clamp_load(kin, c, t, p, fc, mc, d, phi, angle, rel, p_rig)
                force = force - sgn*fc
                moment = moment - sgn*(mc + cross(p - point, fc))
            end associate
        end do
    end subroutine less_clamps

end module hn_sections
