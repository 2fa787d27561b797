!> Shared fixtures of the tests: the reproducible random generator, random
!! trees and small textbook mechanisms.
module hn_test_models
    use hn_kinds, only: wp, zero, one, msglen
    use hn_rotation, only: axis_angle_matrix
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_random, only: rng_t
    use hn_case, only: case_t
    use hn_deck, only: read_case
    implicit none
    private

    public :: rng_t, random_tree, random_inertia, pendulum_tree, elliptic_k
    public :: write_lines, delete_file, read_deck_lines

contains

    !> Write the lines to file fname, each ended by LF.
    subroutine write_lines(fname, lines)
        character(len=*), intent(in) :: fname, lines(:)
        integer :: u, k
        open (newunit=u, file=fname, status='replace', form='unformatted', access='stream')
        do k = 1, size(lines)
            write (u) trim(lines(k))//achar(10)
        end do
        close (u)
    end subroutine write_lines

    !> Delete file fname if it exists.
    subroutine delete_file(fname)
        character(len=*), intent(in) :: fname
        integer :: u, ios
        open (newunit=u, file=fname, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine delete_file

    !> Read a deck given as lines through the whole deck reader (as if from
    !! standard input), by way of the scratch file `scratch`.
    subroutine read_deck_lines(scratch, lines, cs, stat, msg)
        character(len=*), intent(in) :: lines(:), scratch
        type(case_t), intent(out) :: cs
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: msg
        call write_lines(scratch, lines)
        call read_case(scratch, 'stdin', cs, stat, msg)
        call delete_file(scratch)
    end subroutine read_deck_lines

    !> A random centroidal inertia: principal values obeying the triangle
    !! inequality, rotated to random principal axes.
    function random_inertia(rng, scale) result(a)
        type(rng_t), intent(inout) :: rng
        real(wp), intent(in) :: scale
        real(wp) :: a(3, 3), p(3), r(3, 3)
        integer :: i
        p(1) = rng%uniform(0.5_wp, 1.0_wp)
        p(2) = rng%uniform(0.5_wp, 1.0_wp)
        p(3) = rng%uniform(abs(p(1) - p(2)) + 0.1_wp, p(1) + p(2) - 0.05_wp)
        r = axis_angle_matrix([rng%uniform(-2.0_wp, 2.0_wp), rng%uniform(-2.0_wp, 2.0_wp), &
                               rng%uniform(-2.0_wp, 2.0_wp)])
        a = zero
        do i = 1, 3
            a(i, i) = scale*p(i)
        end do
        a = matmul(r, matmul(a, transpose(r)))
        a = 0.5_wp*(a + transpose(a))
    end function random_inertia

    !> A random tree of nb bodies, every coordinate active, with random
    !! parents, masses, inertias and joint offsets.
    subroutine random_tree(tree, nb, rng)
        type(body_tree_t), intent(out) :: tree
        integer, intent(in) :: nb
        type(rng_t), intent(inout) :: rng
        integer :: k, stat
        character(len=msglen) :: msg
        call tree_allocate(tree, nb)
        do k = 1, nb
            if (k == 1) then
                tree%parent(k) = 0
            else
                tree%parent(k) = 1 + int(rng%uniform(zero, one)*(k - 1))
            end if
            tree%mass(k) = rng%uniform(0.3_wp, 4.0_wp)
            tree%inertia(:, :, k) = random_inertia(rng, 0.01_wp)
            tree%joint_parent(:, k) = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), &
                                       rng%uniform(0.0_wp, 0.08_wp)]
            tree%joint_child(:, k) = [rng%uniform(-0.05_wp, 0.05_wp), rng%uniform(-0.05_wp, 0.05_wp), &
                                      rng%uniform(-0.08_wp, 0.0_wp)]
        end do
        call tree_build(tree, stat, msg)
        if (stat /= 0) error stop 'random_tree: '//trim(msg)
    end subroutine random_tree

    !> A chain of nb pendulum links swinging about y: link k has mass m(k),
    !! centroidal inertia about y iyy(k), joint point c(k) above its mass
    !! centre, and the next joint len(k) below its own joint. Only the
    !! rotation about y of each link is active.
    subroutine pendulum_tree(tree, m, iyy, c, len)
        type(body_tree_t), intent(out) :: tree
        real(wp), intent(in) :: m(:), iyy(:), c(:), len(:)
        integer :: k, stat, nb
        character(len=msglen) :: msg
        nb = size(m)
        call tree_allocate(tree, nb)
        do k = 1, nb
            tree%mass(k) = m(k)
            tree%inertia(:, :, k) = zero
            tree%inertia(1, 1, k) = iyy(k)
            tree%inertia(2, 2, k) = iyy(k)
            tree%inertia(3, 3, k) = 0.1_wp*iyy(k)
            tree%joint_child(:, k) = [zero, zero, c(k)]
            if (k > 1) tree%joint_parent(:, k) = [zero, zero, -(len(k - 1) - c(k - 1))]
            tree%active(:, k) = .false.
            tree%active(5, k) = .true.
        end do
        call tree_build(tree, stat, msg)
        if (stat /= 0) error stop 'pendulum_tree: '//trim(msg)
    end subroutine pendulum_tree

    !> Complete elliptic integral of the first kind K(k) by the
    !! arithmetic-geometric mean: K = pi / (2 AGM(1, sqrt(1-k^2))).
    pure real(wp) function elliptic_k(k) result(kk)
        real(wp), intent(in) :: k
        real(wp) :: a, b, an
        integer :: i
        a = one
        b = sqrt(one - k**2)
        do i = 1, 60
            an = 0.5_wp*(a + b)
            b = sqrt(a*b)
            a = an
            if (abs(a - b) < 1.0e-16_wp*a) exit
        end do
        kk = acos(-one)/(2.0_wp*a)
    end function elliptic_k

end module hn_test_models
