!> Recursive forms of Kane's equations for the open tree, in spatial
!! vectors of R about the reference point kin%origin: a motion vector is
!! (angular velocity; velocity of the body point at the origin), a force
!! vector (moment about the origin; force). In this one frame the joint
!! column sj_i of coordinate i is the partial velocity of every body of
!! its subtree, the spatial inertias of bodies simply add, and
!!   a_ij = sj_i . (I_c(k) sj_j)     (composite rigid body, Walker & Orin),
!!   f_i  = sj_i . W(k)              (W: loads minus velocity-dependent inertia
!!                                    forces summed over the subtree of k,
!!                                    the recursive Newton-Euler form of eq 18),
!! k the body of coordinate i. These are eqs 17 and 18 regrouped: the same
!! numbers without the partial-velocity arrays. `articulated_body_solve`
!! (Featherstone's articulated-body algorithm) solves a_FF xddot_F =
!! f_F - a_FP xddot_P in O(n) without forming a_ij at all.
module hn_recursive
    use hn_kinds, only: wp, zero
    use hn_status, only: stat_ok, stat_singular
    use hn_rotation, only: cross, skew
    use hn_tree, only: body_tree_t
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    implicit none
    private

    public :: composite_rigid_body, f_recursive, inertia_times, articulated_body_solve
    public :: aba_work_t, aba_work_allocate

    !> Relative size of a pivot of a joint's articulated inertia D = S^T I^A S
    !! below which the joint axes are taken as dependent (a singular joint).
    real(wp), parameter :: joint_pivot_min = 1.0e-13_wp

    !> Work arrays of articulated_body_solve, sized once for a tree (no
    !! allocation in the solve itself).
    type :: aba_work_t
        real(wp), allocatable :: ia(:, :, :)   !! (6,6,nb) articulated inertias
        real(wp), allocatable :: pa(:, :)      !! (6,nb) articulated bias forces
        real(wp), allocatable :: c(:, :)       !! (6,nb) known acceleration of each joint's prescribed columns
        real(wp), allocatable :: sa(:, :)      !! (6,nb) spatial accelerations
        real(wp), allocatable :: u(:, :, :)    !! (6,6,nb) U = I^A S of each joint
        real(wp), allocatable :: dl(:, :, :)   !! (6,6,nb) Cholesky factor of D = S^T U
        real(wp), allocatable :: uu(:, :)      !! (6,nb) u = tau - S^T p^A
        integer, allocatable :: nf(:)          !! (nb) free columns of each joint
        integer, allocatable :: cols(:, :)     !! (6,nb) their coordinate numbers
    end type aba_work_t

contains

    !> Size the work arrays of articulated_body_solve for a tree.
    pure subroutine aba_work_allocate(tree, work)
        type(body_tree_t), intent(in) :: tree      !! the body tree
        type(aba_work_t), intent(out) :: work      !! arrays sized for its bodies
        integer :: nb
        nb = tree%nbody
        allocate (work%ia(6, 6, nb), work%pa(6, nb), work%c(6, nb), work%sa(6, nb), work%u(6, 6, nb))
        allocate (work%dl(6, 6, nb), work%uu(6, nb), work%nf(nb), work%cols(6, nb))
    end subroutine aba_work_allocate

    !> Spatial inertia of body k about the origin in compact form: mass m,
    !! first moment h = m c and rotational inertia J = I_c + m (|c|^2 1 - c c^T),
    !! c the mass centre relative to the origin.
    pure subroutine body_inertia(tree, kin, k, m, h, j)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        integer, intent(in) :: k
        real(wp), intent(out) :: m, h(3), j(3, 3)
        real(wp) :: c(3)
        integer :: i
        c = kin%r(:, k) - kin%origin
        m = tree%mass(k)
        h = m*c
        do i = 1, 3
            j(:, i) = kin%inertia_r(:, i, k) - h*c(i)
            j(i, i) = j(i, i) + m*dot_product(c, c)
        end do
    end subroutine body_inertia

    !> Force vector I s of the compact spatial inertia (m, h, J) for the
    !! motion vector s = (w; v): (J w + h x v; m v - h x w).
    pure function inertia_apply(m, h, j, s) result(f)
        real(wp), intent(in) :: m, h(3), j(3, 3), s(6)
        real(wp) :: f(6)
        f(1:3) = matmul(j, s(1:3)) + cross(h, s(4:6))
        f(4:6) = m*s(4:6) - cross(h, s(1:3))
    end function inertia_apply

    !> a_ij of all active coordinates by the composite-rigid-body recursion:
    !! composite inertias passed from child to parent, then for each
    !! coordinate i of body k the force F = I_c(k) sj_i projected on the
    !! columns of k's chain. The same matrix as eq 17 (hn_kane's a_ij).
    pure subroutine composite_rigid_body(tree, kin, a)
        type(body_tree_t), intent(in) :: tree   !! masses, parents and coordinate numbering of the bodies
        type(kinematics_t), intent(in) :: kin   !! joint columns sj, mass centres and inertias in R (body_kinematics)
        real(wp), intent(out) :: a(:, :)        !! (n,n) symmetric positive definite
        real(wp) :: cm(tree%nbody), ch(3, tree%nbody), cj(3, 3, tree%nbody), f(6)
        integer :: ik, k, p, m, i, jj, j
        do k = 1, tree%nbody
            call body_inertia(tree, kin, k, cm(k), ch(:, k), cj(:, :, k))
        end do
        do ik = tree%nbody, 1, -1
            k = tree%order(ik)
            p = tree%parent(k)
            if (p == 0) cycle
            cm(p) = cm(p) + cm(k)
            ch(:, p) = ch(:, p) + ch(:, k)
            cj(:, :, p) = cj(:, :, p) + cj(:, :, k)
        end do
        a = zero
        do k = 1, tree%nbody
            do m = 1, 6
                i = tree%dof_index(m, k)
                if (i == 0) cycle
                f = inertia_apply(cm(k), ch(:, k), cj(:, :, k), kin%sj(:, i))
                do jj = 1, tree%chain_len(k)
                    j = tree%chain(jj, k)
                    if (tree%dof_body(j) == k .and. j > i) cycle   ! own pairs once
                    a(j, i) = dot_product(kin%sj(:, j), f)
                    a(i, j) = a(j, i)
                end do
            end do
        end do
    end subroutine composite_rigid_body

    !> Spatial force of the loads on body k minus its velocity-dependent
    !! inertia forces (the eq 18 terms not proportional to xddot), about the
    !! origin.
    pure function bias_wrench(tree, kin, loads, k) result(w)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        type(body_loads_t), intent(in) :: loads
        integer, intent(in) :: k
        real(wp) :: w(6), iw(3), ir(3, 3), om(3)
        ir = kin%inertia_r(:, :, k)     ! fixed-size copies keep the products inline
        om = kin%omega(:, k)
        iw = matmul(ir, om)
        w(4:6) = loads%force(:, k) - tree%mass(k)*kin%a0(:, k)
        w(1:3) = loads%moment(:, k) - matmul(ir, kin%alpha0(:, k)) - cross(om, iw) &
                 + cross(kin%r(:, k) - kin%origin, w(4:6))
    end function bias_wrench

    !> Sum of per-body spatial forces over each body's subtree (leaves first).
    pure subroutine subtree_sums(tree, w)
        type(body_tree_t), intent(in) :: tree
        real(wp), intent(inout) :: w(:, :)     !! (6, nb) in: own, out: subtree sums
        integer :: ik, k
        do ik = tree%nbody, 1, -1
            k = tree%order(ik)
            if (tree%parent(k) > 0) w(:, tree%parent(k)) = w(:, tree%parent(k)) + w(:, k)
        end do
    end subroutine subtree_sums

    !> f_i (eq 18) by the backward recursion: body loads minus the
    !! velocity-dependent inertia forces summed over each subtree and
    !! projected on the joint columns, plus the generalized forces on the
    !! coordinates. O(n), no partial-velocity arrays.
    pure subroutine f_recursive(tree, kin, loads, f)
        type(body_tree_t), intent(in) :: tree     !! masses, parents and coordinate numbering of the bodies
        type(kinematics_t), intent(in) :: kin     !! joint columns sj and velocity terms a0, alpha0 (body_kinematics)
        type(body_loads_t), intent(in) :: loads   !! body forces [N], moments [N m], generalized forces q
        real(wp), intent(out) :: f(:)             !! (n) f_i [N or N m]
        real(wp) :: w(6, tree%nbody)
        integer :: k, i
        do k = 1, tree%nbody
            w(:, k) = bias_wrench(tree, kin, loads, k)
        end do
        call subtree_sums(tree, w)
        do i = 1, size(f)
            f(i) = dot_product(kin%sj(:, i), w(:, tree%dof_body(i))) + loads%q(i)
        end do
    end subroutine f_recursive

    !> The product a_ij v_j for all active coordinates, by one forward pass
    !! (spatial accelerations sj v) and one backward pass (inertia forces),
    !! O(n) without a_ij.
    pure function inertia_times(tree, kin, v) result(av)
        type(body_tree_t), intent(in) :: tree   !! masses, parents and coordinate numbering of the bodies
        type(kinematics_t), intent(in) :: kin   !! joint columns sj, mass centres and inertias in R (body_kinematics)
        real(wp), intent(in) :: v(:)            !! (n) the vector multiplied, one entry per active coordinate
        real(wp) :: av(size(v))
        real(wp) :: sa(6, tree%nbody), w(6, tree%nbody), m, h(3), j(3, 3)
        integer :: ik, k, mm, i
        do ik = 1, tree%nbody
            k = tree%order(ik)
            sa(:, k) = zero
            if (tree%parent(k) > 0) sa(:, k) = sa(:, tree%parent(k))
            do mm = 1, 6
                i = tree%dof_index(mm, k)
                if (i > 0) sa(:, k) = sa(:, k) + kin%sj(:, i)*v(i)
            end do
            call body_inertia(tree, kin, k, m, h, j)
            w(:, k) = inertia_apply(m, h, j, sa(:, k))
        end do
        call subtree_sums(tree, w)
        do i = 1, size(v)
            av(i) = dot_product(kin%sj(:, i), w(:, tree%dof_body(i)))
        end do
    end function inertia_times

    !> Articulated-body algorithm (Featherstone): xddot of the free
    !! coordinates from the loads, with the prescribed coordinates' xddot
    !! given, in O(n); also the generalized constraint forces
    !! lambda_P = a_P. xddot - f_P of the prescribed coordinates. The joint of
    !! a body spans its free columns; its prescribed columns add a known
    !! acceleration. stat = stat_singular (bad_body set) when a joint's
    !! articulated inertia S^T I^A S is singular.
    pure subroutine articulated_body_solve(tree, kin, loads, prescribed, xdd, lambda, stat, bad_body, work)
        type(body_tree_t), intent(in) :: tree     !! masses, parents and coordinate numbering of the bodies
        type(kinematics_t), intent(in) :: kin     !! joint columns sj and velocity terms a0, alpha0 (body_kinematics)
        type(body_loads_t), intent(in) :: loads   !! body forces [N], moments [N m], generalized forces q
        logical, intent(in) :: prescribed(:)      !! (n) coordinate is prescribed
        real(wp), intent(inout) :: xdd(:)         !! (n) in: prescribed entries; out: free entries filled
        real(wp), intent(out) :: lambda(:)        !! (n) constraint forces on prescribed coordinates, 0 on free
        integer, intent(out) :: stat              !! stat_ok, or stat_singular (bad_body's joint)
        integer, intent(out) :: bad_body          !! body of a singular joint (0: none)
        type(aba_work_t), intent(inout) :: work   !! work arrays from aba_work_allocate for this tree
        call aba_sweeps(tree, kin, loads, prescribed, xdd, lambda, stat, bad_body, work%ia, work%pa, work%c, &
                        work%sa, work%u, work%dl, work%uu, work%nf, work%cols)
    end subroutine articulated_body_solve

    !> The two sweeps of articulated_body_solve on explicit-shape work arrays.
    pure subroutine aba_sweeps(tree, kin, loads, prescribed, xdd, lambda, stat, bad_body, ia, pa, c, sa, u, dl, uu, &
                               nf, cols)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        type(body_loads_t), intent(in) :: loads
        logical, intent(in) :: prescribed(:)
        real(wp), intent(inout) :: xdd(:)
        real(wp), intent(out) :: lambda(:)
        integer, intent(out) :: stat, bad_body
        real(wp), intent(out) :: ia(6, 6, tree%nbody), pa(6, tree%nbody), c(6, tree%nbody), sa(6, tree%nbody)
        real(wp), intent(out) :: u(6, 6, tree%nbody), dl(6, 6, tree%nbody), uu(6, tree%nbody)
        integer, intent(out) :: nf(tree%nbody), cols(6, tree%nbody)
        real(wp) :: fj(6)
        integer :: ik, k, p, m, j
        stat = stat_ok
        bad_body = 0
        lambda = zero
        do k = 1, tree%nbody
            call spatial_inertia6(tree, kin, k, ia(:, :, k))
            pa(:, k) = -bias_wrench(tree, kin, loads, k)
            nf(k) = 0
            c(:, k) = zero
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j == 0) cycle
                if (prescribed(j)) then
                    c(:, k) = c(:, k) + kin%sj(:, j)*xdd(j)
                else
                    nf(k) = nf(k) + 1
                    cols(nf(k), k) = j
                end if
            end do
        end do
        ! backward pass: articulated inertias and bias forces
        do ik = tree%nbody, 1, -1
            k = tree%order(ik)
            p = tree%parent(k)
            if (p > 0) then
                call joint_reduce(kin%sj, loads%q, cols(:, k), nf(k), c(:, k), ia(:, :, k), pa(:, k), u(:, :, k), &
                                  dl(:, :, k), uu(:, k), stat, ia(:, :, p), pa(:, p))
            else
                call joint_reduce(kin%sj, loads%q, cols(:, k), nf(k), c(:, k), ia(:, :, k), pa(:, k), u(:, :, k), &
                                  dl(:, :, k), uu(:, k), stat)
            end if
            if (stat /= stat_ok) then
                bad_body = k
                return
            end if
        end do
        ! forward pass: accelerations
        do ik = 1, tree%nbody
            k = tree%order(ik)
            p = tree%parent(k)
            sa(:, k) = c(:, k)
            if (p > 0) sa(:, k) = sa(:, k) + sa(:, p)
            call joint_accelerations(kin%sj, cols(:, k), nf(k), u(:, :, k), dl(:, :, k), uu(:, k), sa(:, k), xdd)
            fj = matmul(ia(:, :, k), sa(:, k)) + pa(:, k)
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j == 0) cycle
                if (prescribed(j)) lambda(j) = dot_product(kin%sj(:, j), fj) - loads%q(j)
            end do
        end do
    end subroutine aba_sweeps

    !> ABA backward step of one joint with free columns sj(:, cols(1:n)): U = I^A S,
    !! D = S^T U factored (L L^T), u = tau - S^T p^A; the articulated inertia
    !! I^a = I^A - U D^-1 U^T and bias p^a = p^A + I^a c + U D^-1 u are added
    !! to the parent's (when given). Fixed 6x6 arrays throughout: the
    !! products stay inline.
    pure subroutine joint_reduce(sj, tau, cols, n, c, ia, pa, u, dl, uu, stat, ia_parent, pa_parent)
        real(wp), intent(in) :: sj(:, :), tau(:)
        integer, intent(in) :: cols(6), n
        real(wp), intent(in) :: c(6), ia(6, 6), pa(6)
        real(wp), intent(out) :: u(6, 6), dl(6, 6), uu(6)
        integer, intent(out) :: stat
        real(wp), intent(inout), optional :: ia_parent(6, 6), pa_parent(6)
        real(wp) :: s(6, 6), yt(6, 6), ylin(6), iat(6, 6), scale, acc
        integer :: a, b, i
        stat = stat_ok     ! only columns 1..n of u, the lower n x n of dl and uu(1:n) are set and read
        do a = 1, n
            s(:, a) = sj(:, cols(a))
            u(:, a) = matmul(ia, s(:, a))
            uu(a) = tau(cols(a)) - dot_product(s(:, a), pa)
        end do
        do a = 1, n      ! D = S^T U is symmetric: its lower triangle is all the factorization reads
            do b = 1, a
                dl(a, b) = dot_product(s(:, a), u(:, b))
            end do
        end do
        if (n > 0) then
            scale = zero
            do a = 1, n
                scale = max(scale, abs(dl(a, a)))
            end do
            call small_cholesky(dl, n, scale, stat)
            if (stat /= stat_ok) return
        end if
        if (.not. present(ia_parent)) return
        ! Y = L^-1 U^T (n x 6), held transposed (yt = Y^T): I^a = I^A - Y^T Y;
        ! p^a = p^A + I^a c + Y^T (L^-1 u); the seven right-hand sides in one forward substitution
        do a = 1, n
            yt(:, a) = u(:, a)
            ylin(a) = uu(a)
            do b = 1, a - 1
                yt(:, a) = yt(:, a) - dl(a, b)*yt(:, b)
                ylin(a) = ylin(a) - dl(a, b)*ylin(b)
            end do
            yt(:, a) = yt(:, a)/dl(a, a)
            ylin(a) = ylin(a)/dl(a, a)
        end do
        do b = 1, 6
            do a = 1, b      ! symmetric: the upper triangle, mirrored
                acc = zero
                do i = 1, n
                    acc = acc + yt(a, i)*yt(b, i)
                end do
                iat(a, b) = ia(a, b) - acc
                iat(b, a) = iat(a, b)
            end do
        end do
        ia_parent = ia_parent + iat
        pa_parent = pa_parent + pa + matmul(iat, c)
        do a = 1, 6
            acc = zero
            do i = 1, n
                acc = acc + yt(a, i)*ylin(i)
            end do
            pa_parent(a) = pa_parent(a) + acc
        end do
    end subroutine joint_reduce

    !> ABA forward step of one joint: xddot_F = D^-1 (u - U^T a') and
    !! a = a' + S xddot_F (sa holds a' on entry, a on return).
    pure subroutine joint_accelerations(sj, cols, n, u, dl, uu, sa, xdd)
        real(wp), intent(in) :: sj(:, :)
        integer, intent(in) :: cols(6), n
        real(wp), intent(in) :: u(6, 6), dl(6, 6), uu(6)
        real(wp), intent(inout) :: sa(6), xdd(:)
        real(wp) :: r(6)
        integer :: a
        do a = 1, n
            r(a) = uu(a) - dot_product(u(:, a), sa)
        end do
        call forward_subst(dl, n, r)
        call backward_subst(dl, n, r)
        do a = 1, n
            xdd(cols(a)) = r(a)
            sa = sa + sj(:, cols(a))*r(a)
        end do
    end subroutine joint_accelerations

    !> Full 6x6 spatial inertia of body k about the origin:
    !! [J, [h]x; -[h]x, m 1] acting on (w; v).
    pure subroutine spatial_inertia6(tree, kin, k, i6)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        integer, intent(in) :: k
        real(wp), intent(out) :: i6(6, 6)
        real(wp) :: m, h(3), j(3, 3), hx(3, 3)
        integer :: a
        call body_inertia(tree, kin, k, m, h, j)
        hx = skew(h)
        i6 = zero
        i6(1:3, 1:3) = j
        i6(1:3, 4:6) = hx
        i6(4:6, 1:3) = -hx
        do a = 4, 6
            i6(a, a) = m
        end do
    end subroutine spatial_inertia6

    !> In-place Cholesky factor L (lower) of the leading n x n block of a
    !! small SPD matrix; stat_singular when a pivot falls below
    !! joint_pivot_min times `scale`.
    pure subroutine small_cholesky(d, n, scale, stat)
        real(wp), intent(inout) :: d(6, 6)
        integer, intent(in) :: n
        real(wp), intent(in) :: scale
        integer, intent(out) :: stat
        integer :: i, j
        real(wp) :: s
        stat = stat_ok
        do j = 1, n
            s = d(j, j) - dot_product(d(j, 1:j - 1), d(j, 1:j - 1))
            if (.not. (s > joint_pivot_min*scale)) then
                stat = stat_singular
                return
            end if
            d(j, j) = sqrt(s)
            do i = j + 1, n
                d(i, j) = (d(i, j) - dot_product(d(i, 1:j - 1), d(j, 1:j - 1)))/d(j, j)
            end do
        end do
    end subroutine small_cholesky

    !> Solve L y = b in place for the leading n entries (L lower triangular).
    pure subroutine forward_subst(l, n, b)
        real(wp), intent(in) :: l(6, 6)
        integer, intent(in) :: n
        real(wp), intent(inout) :: b(6)
        integer :: i
        do i = 1, n
            b(i) = (b(i) - dot_product(l(i, 1:i - 1), b(1:i - 1)))/l(i, i)
        end do
    end subroutine forward_subst

    !> Solve L^T x = b in place for the leading n entries (L lower triangular).
    pure subroutine backward_subst(l, n, b)
        real(wp), intent(in) :: l(6, 6)
        integer, intent(in) :: n
        real(wp), intent(inout) :: b(6)
        integer :: i
        do i = n, 1, -1
            b(i) = (b(i) - dot_product(l(i + 1:n, i), b(i + 1:n)))/l(i, i)
        end do
    end subroutine backward_subst

end module hn_recursive
