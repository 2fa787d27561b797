!> Body-tree tables of an open tree of rigid bodies (the paper's "body
!! connection array" and geometry), and the numbering of its coordinates.
!!
!! Body k (1..nbody) hangs from body `parent(k)`; parent 0 is the inertial
!! frame R (X forward, Y left, Z up). Each body has six relative coordinates,
!! local numbers 1..6:
!!   1-3  translation of the joint point of k relative to the joint point fixed
!!        in the parent, along the parent's axes [m];
!!   4-6  Bryant angles (x, then y', then z'') of k relative to the parent [rad].
!! Each coordinate is either active (a generalized coordinate, free or
!! prescribed) or locked at its reference value `q_ref`. Active coordinates
!! are numbered body by body, local order within a body, so the full 54-DOF
!! head/neck model has x_(6(k-1)+m) as in the paper.
module hn_tree
    use hn_kinds, only: wp, zero, msglen
    use hn_status, only: stat_ok, stat_bad_model
    implicit none
    private

    public :: body_tree_t, tree_allocate, tree_build, dof_label

    integer, parameter, public :: name_len = 12

    !> Geometry, inertia and connectivity of the tree.
    type :: body_tree_t
        integer :: nbody = 0                       !! number of bodies
        integer :: ndof = 0                        !! number of active coordinates
        character(len=name_len), allocatable :: name(:)  !! body names
        integer, allocatable :: parent(:)          !! parent body (0 = inertial frame)
        real(wp), allocatable :: mass(:)           !! mass [kg]
        real(wp), allocatable :: inertia(:, :, :)  !! centroidal inertia in body frame [kg m^2]
        real(wp), allocatable :: joint_parent(:, :) !! joint point in the parent frame, from the parent's mass centre [m]
        real(wp), allocatable :: joint_child(:, :)  !! joint point in the body frame, from its own mass centre [m]
        real(wp), allocatable :: q_ref(:, :)       !! (6, nbody) reference value of every coordinate
        logical, allocatable :: active(:, :)       !! (6, nbody) coordinate is a generalized coordinate
        integer, allocatable :: dof_index(:, :)    !! (6, nbody) active number, 0 when locked
        integer, allocatable :: dof_body(:)        !! body of each active coordinate
        integer, allocatable :: dof_local(:)       !! local number (1..6) of each active coordinate
        integer, allocatable :: order(:)           !! bodies ordered parents first
        integer, allocatable :: depth(:)           !! number of bodies from the root (root = 1)
        integer, allocatable :: chain_len(:)       !! number of active coordinates of k and its ancestors
        integer, allocatable :: chain(:, :)        !! (ndof, nbody) those coordinates, ascending
        logical, allocatable :: chain_contiguous(:) !! the chain is one run of consecutive numbers
        real(wp), allocatable :: inertia_factor(:, :, :) !! (3,3,nbody) L with inertia = L L^T (Cholesky)
    end type body_tree_t

contains

    !> Allocate the tables for `n` bodies with neutral values: unit mass and
    !! inertia, every coordinate active and zero, a chain of bodies.
    pure subroutine tree_allocate(tree, n)
        type(body_tree_t), intent(out) :: tree   !! tables for n bodies with neutral values
        integer, intent(in) :: n                 !! number of bodies
        integer :: k
        tree%nbody = n
        allocate (tree%name(n), tree%parent(n), tree%mass(n), tree%inertia(3, 3, n))
        allocate (tree%joint_parent(3, n), tree%joint_child(3, n), tree%q_ref(6, n))
        allocate (tree%active(6, n), tree%dof_index(6, n))
        do k = 1, n
            write (tree%name(k), '(a,i0)') 'B', k
            tree%parent(k) = k - 1
            tree%inertia(:, :, k) = zero
            tree%inertia(1, 1, k) = 1.0_wp
            tree%inertia(2, 2, k) = 1.0_wp
            tree%inertia(3, 3, k) = 1.0_wp
        end do
        tree%mass = 1.0_wp
        tree%joint_parent = zero
        tree%joint_child = zero
        tree%q_ref = zero
        tree%active = .true.
        tree%dof_index = 0
    end subroutine tree_allocate

    !> Check the tables and build the derived ones: topological order, depth,
    !! active-coordinate numbering and each body's chain of coordinates.
    !! Rejects parents out of range, loops, non-positive mass and inertia
    !! that is not symmetric positive definite.
    pure subroutine tree_build(tree, stat, errmsg, bad_body)
        type(body_tree_t), intent(inout) :: tree     !! tables filled; out: order, numbering and chains as well
        integer, intent(out) :: stat                 !! stat_ok, or stat_bad_model with errmsg
        character(len=msglen), intent(out) :: errmsg !! reason on failure
        integer, intent(out), optional :: bad_body   !! the body at fault (0 when none is)
        integer :: n, k, m, p, steps, pos, j
        logical, allocatable :: placed(:)
        real(wp) :: a(3, 3), d1, d2, d3, scale

        stat = stat_ok
        if (present(bad_body)) bad_body = 0
        errmsg = ''
        n = tree%nbody
        if (n < 1) then
            stat = stat_bad_model; errmsg = 'tree has no bodies'; return
        end if
        do k = 1, n
            p = tree%parent(k)
            if (p < 0 .or. p > n .or. p == k) then
                stat = stat_bad_model
                if (present(bad_body)) bad_body = k
                write (errmsg, '(a,i0,3a,i0,a,i0)') 'body ', k, ' (', trim(tree%name(k)), &
                    ') has parent ', p, '; expected 0..', n
                if (p == k) errmsg = trim(errmsg)//' other than itself'
                return
            end if
            ! follow the parents: a tree reaches R within n steps
            steps = 0
            do while (p /= 0)
                p = tree%parent(p)
                steps = steps + 1
                if (steps > n) then
                    stat = stat_bad_model
                if (present(bad_body)) bad_body = k
                    write (errmsg, '(a,i0,3a)') 'body ', k, ' (', trim(tree%name(k)), &
                        ') lies on a loop of parents; the bodies must form an open tree rooted at 0'
                    return
                end if
            end do
            if (.not. (tree%mass(k) > zero) .or. tree%mass(k) > huge(1.0_wp)) then
                stat = stat_bad_model
                if (present(bad_body)) bad_body = k
                write (errmsg, '(a,i0,3a,es10.3,a)') 'body ', k, ' (', trim(tree%name(k)), &
                    ') has mass ', tree%mass(k), ' kg; expected a positive finite mass'
                return
            end if
            a = tree%inertia(:, :, k)
            scale = max(abs(a(1, 1)), abs(a(2, 2)), abs(a(3, 3)), tiny(1.0_wp))
            d1 = a(1, 1)
            d2 = a(1, 1)*a(2, 2) - a(1, 2)*a(2, 1)
            d3 = a(1, 1)*(a(2, 2)*a(3, 3) - a(2, 3)*a(3, 2)) - a(1, 2)*(a(2, 1)*a(3, 3) - a(2, 3)*a(3, 1)) &
                 + a(1, 3)*(a(2, 1)*a(3, 2) - a(2, 2)*a(3, 1))
            if (maxval(abs(a - transpose(a))) > 1.0e-12_wp*scale .or. .not. (d1 > zero) &
                .or. .not. (d2 > zero) .or. .not. (d3 > zero) .or. .not. (scale < huge(1.0_wp))) then
                stat = stat_bad_model
                if (present(bad_body)) bad_body = k
                write (errmsg, '(a,i0,3a)') 'body ', k, ' (', trim(tree%name(k)), &
                    ') has an inertia matrix that is not symmetric positive definite'
                return
            end if
        end do

        ! topological order: parents before children
        if (allocated(tree%order)) deallocate (tree%order)
        if (allocated(tree%depth)) deallocate (tree%depth)
        allocate (tree%order(n), tree%depth(n), placed(0:n))
        placed = .false.
        placed(0) = .true.
        pos = 0
        do while (pos < n)
            do k = 1, n
                if (.not. placed(k) .and. placed(tree%parent(k))) then
                    pos = pos + 1
                    tree%order(pos) = k
                    placed(k) = .true.
                    if (tree%parent(k) == 0) then
                        tree%depth(k) = 1
                    else
                        tree%depth(k) = tree%depth(tree%parent(k)) + 1
                    end if
                end if
            end do
        end do

        ! active coordinates numbered body by body
        tree%ndof = count(tree%active)
        if (allocated(tree%dof_body)) deallocate (tree%dof_body, tree%dof_local)
        allocate (tree%dof_body(tree%ndof), tree%dof_local(tree%ndof))
        j = 0
        tree%dof_index = 0
        do k = 1, n
            do m = 1, 6
                if (tree%active(m, k)) then
                    j = j + 1
                    tree%dof_index(m, k) = j
                    tree%dof_body(j) = k
                    tree%dof_local(j) = m
                end if
            end do
        end do

        ! chain of each body: own and ancestors' active coordinates, ascending
        if (allocated(tree%chain)) deallocate (tree%chain, tree%chain_len)
        allocate (tree%chain(max(tree%ndof, 1), n), tree%chain_len(n))
        tree%chain = 0
        do k = 1, n
            pos = 0
            do j = 1, tree%ndof
                p = k
                do while (p /= 0)
                    if (tree%dof_body(j) == p) then
                        pos = pos + 1
                        tree%chain(pos, k) = j
                        exit
                    end if
                    p = tree%parent(p)
                end do
            end do
            tree%chain_len(k) = pos
        end do
        if (allocated(tree%chain_contiguous)) deallocate (tree%chain_contiguous, tree%inertia_factor)
        allocate (tree%chain_contiguous(n), tree%inertia_factor(3, 3, n))
        do k = 1, n
            pos = tree%chain_len(k)
            tree%chain_contiguous(k) = .true.
            if (pos > 0) tree%chain_contiguous(k) = tree%chain(pos, k) - tree%chain(1, k) + 1 == pos
            tree%inertia_factor(:, :, k) = cholesky3(tree%inertia(:, :, k))
        end do
    contains
        pure function cholesky3(m) result(l)
            real(wp), intent(in) :: m(3, 3)
            real(wp) :: l(3, 3)
            l = zero
            l(1, 1) = sqrt(m(1, 1))
            l(2, 1) = m(2, 1)/l(1, 1)
            l(3, 1) = m(3, 1)/l(1, 1)
            l(2, 2) = sqrt(m(2, 2) - l(2, 1)**2)
            l(3, 2) = (m(3, 2) - l(3, 1)*l(2, 1))/l(2, 2)
            l(3, 3) = sqrt(m(3, 3) - l(3, 1)**2 - l(3, 2)**2)
        end function cholesky3
    end subroutine tree_build

    !> Readable label of active coordinate j, e.g. "HEAD.rx".
    pure function dof_label(tree, j) result(s)
        type(body_tree_t), intent(in) :: tree   !! a built tree
        integer, intent(in) :: j                !! active coordinate number
        character(len=name_len + 3) :: s
        character(len=2), parameter :: local(6) = ['tx', 'ty', 'tz', 'rx', 'ry', 'rz']
        s = trim(tree%name(tree%dof_body(j)))//'.'//local(tree%dof_local(j))
    end function dof_label

end module hn_tree
