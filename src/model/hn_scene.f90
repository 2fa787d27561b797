!> Model reduction for a scene: merging adjacent bodies into one rigid body
!! (mass, mass centre and inertia combined by the parallel-axis theorem in
!! the neutral posture) and the sagittal shorthand. The engine then builds
!! and integrates only the bodies and coordinates that remain.
module hn_scene
    use hn_kinds, only: wp, zero, msglen
    use hn_status, only: stat_ok, stat_bad_model
    use hn_tree, only: body_tree_t, tree_allocate
    implicit none
    private

    public :: merge_bodies, lock_sagittal

contains

    !> Lock the out-of-plane coordinates (TY, RX, RZ) of every body: the
    !! sagittal scene keeps TX, TZ and RY, 3 of 6 per body.
    pure subroutine lock_sagittal(tree)
        type(body_tree_t), intent(inout) :: tree   !! tables before tree_build; out: TY, RX, RZ inactive on every body
        tree%active(2, :) = .false.
        tree%active(4, :) = .false.
        tree%active(6, :) = .false.
    end subroutine lock_sagittal

    !> Merge the bodies `absorbed` into `survivor` (tables before tree_build).
    !! Each absorbed body must hang from the survivor or from another absorbed
    !! body, and be aligned with the survivor in the neutral posture (its
    !! neutral relative rotations zero). The merged body keeps the survivor's
    !! axes and name; its origin moves to the combined mass centre. On return
    !! new_index(k) is the number of old body k in the reduced tree and
    !! shift(:, k) is what to add to a point given in old body k's frame.
    pure subroutine merge_bodies(tree, survivor, absorbed, new_index, shift, stat, errmsg)
        type(body_tree_t), intent(inout) :: tree        !! tables before tree_build; out: the reduced tree
        integer, intent(in) :: survivor                 !! the body that remains (keeps its axes and name)
        integer, intent(in) :: absorbed(:)              !! the bodies merged into it
        integer, intent(out) :: new_index(tree%nbody)   !! number in the reduced tree of each old body
        real(wp), intent(out) :: shift(3, tree%nbody)   !! add to a point in old body k's frame [m]
        integer, intent(out) :: stat                    !! stat_ok, or stat_bad_model (errmsg says why)
        character(len=msglen), intent(out) :: errmsg    !! why the bodies cannot be merged ('' when stat_ok)
        type(body_tree_t) :: old
        logical :: inset(tree%nbody), done(tree%nbody)
        real(wp) :: pos(3, tree%nbody), g(3), mtot, inertia(3, 3), d(3), eye(3, 3)
        integer :: k, p, n, nb, pass, i
        stat = stat_ok; errmsg = ''
        nb = tree%nbody
        inset = .false.
        inset(survivor) = .true.
        inset(absorbed) = .true.
        ! neutral mass-centre positions of the set in the survivor's frame
        pos = zero
        done = .false.
        done(survivor) = .true.
        do pass = 1, size(absorbed) + 1
            do i = 1, size(absorbed)
                k = absorbed(i)
                if (done(k)) cycle
                p = tree%parent(k)
                if (p == 0) then
                    stat = stat_bad_model
                else if (.not. inset(p)) then
                    stat = stat_bad_model
                end if
                if (stat /= 0) then
                    write (errmsg, '(5a)') 'body ', trim(tree%name(k)), ' does not hang from ', &
                        trim(tree%name(survivor)), ' or another body of the MERGE card'
                    return
                end if
                if (.not. done(p)) cycle
                if (any(tree%q_ref(4:6, k) /= zero)) then
                    stat = stat_bad_model
                    write (errmsg, '(3a)') 'body ', trim(tree%name(k)), &
                        ' has a neutral rotation relative to its parent; MERGE needs the bodies aligned in the '// &
                        'neutral posture'
                    return
                end if
                pos(:, k) = pos(:, p) + tree%joint_parent(:, k) + tree%q_ref(1:3, k) - tree%joint_child(:, k)
                done(k) = .true.
            end do
        end do
        mtot = sum(tree%mass, mask=inset)
        g = zero
        do k = 1, nb
            if (inset(k)) g = g + tree%mass(k)*pos(:, k)
        end do
        g = g/mtot
        eye = zero
        eye(1, 1) = 1; eye(2, 2) = 1; eye(3, 3) = 1
        inertia = zero
        do k = 1, nb
            if (.not. inset(k)) cycle
            d = pos(:, k) - g
            inertia = inertia + tree%inertia(:, :, k) + tree%mass(k)*(dot_product(d, d)*eye - &
                                                                       spread(d, 2, 3)*spread(d, 1, 3))
        end do
        ! points: old body k's frame -> merged frame (same axes, origin at g)
        shift = zero
        do k = 1, nb
            if (inset(k)) shift(:, k) = pos(:, k) - g
        end do
        ! renumber: the survivor keeps its place, absorbed bodies disappear
        n = 0
        do k = 1, nb
            if (inset(k) .and. k /= survivor) then
                new_index(k) = 0
            else
                n = n + 1
                new_index(k) = n
            end if
        end do
        do k = 1, nb
            if (inset(k) .and. k /= survivor) new_index(k) = new_index(survivor)
        end do
        old = tree
        call tree_allocate(tree, n)
        do k = 1, nb
            if (inset(k) .and. k /= survivor) cycle
            i = new_index(k)
            tree%name(i) = old%name(k)
            tree%mass(i) = old%mass(k)
            tree%inertia(:, :, i) = old%inertia(:, :, k)
            tree%joint_parent(:, i) = old%joint_parent(:, k)
            tree%joint_child(:, i) = old%joint_child(:, k)
            tree%q_ref(:, i) = old%q_ref(:, k)
            tree%active(:, i) = old%active(:, k)
            p = old%parent(k)
            tree%parent(i) = 0
            if (p > 0) then
                tree%parent(i) = new_index(p)
                ! a child of a body of the set: its joint point moves with that body's frame
                if (inset(p)) tree%joint_parent(:, i) = old%joint_parent(:, k) + shift(:, p)
            end if
        end do
        i = new_index(survivor)
        tree%mass(i) = mtot
        tree%inertia(:, :, i) = 0.5_wp*(inertia + transpose(inertia))
        tree%joint_child(:, i) = old%joint_child(:, survivor) + shift(:, survivor)
    end subroutine merge_bodies

end module hn_scene
