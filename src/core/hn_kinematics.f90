!> Kinematics of the open tree by the recursive algorithm of the paper:
!! transformation matrices, angular velocities, partial angular velocities
!! omega_pjk and partial velocities v_pjk of every mass centre (eqs 15-16),
!! and their time derivatives.
!!
!! Index order in the arrays is (k, j, p): component k in R, coordinate j,
!! body p, so `w(:, j, p)` is the partial angular velocity of body p with
!! respect to xdot_j. Entries outside a body's chain are zero and never read.
module hn_kinematics
    use hn_kinds, only: wp, zero, half
    use hn_rotation, only: cross, bryant_matrix, bryant_axes
    use hn_tree, only: body_tree_t
    implicit none
    private

    public :: kinematics_t, kinematics_allocate, partial_velocities, body_kinematics
    public :: body_accelerations, kinetic_energy, linear_momentum, angular_momentum
    public :: body_coordinates

    !> Kinematic state of every body, all vectors in R components.
    type :: kinematics_t
        integer :: nbody = 0, ndof = 0
        real(wp), allocatable :: s(:, :, :)        !! (3,3,nb) body-to-R transformation matrix
        real(wp), allocatable :: r(:, :)           !! (3,nb) mass-centre position [m]
        real(wp), allocatable :: v(:, :)           !! (3,nb) mass-centre velocity [m/s]
        real(wp), allocatable :: omega(:, :)       !! (3,nb) angular velocity [rad/s]
        real(wp), allocatable :: joint(:, :)       !! (3,nb) joint point of the body [m]
        real(wp), allocatable :: inertia_r(:, :, :) !! (3,3,nb) centroidal inertia in R [kg m^2]
        real(wp), allocatable :: axes(:, :, :)     !! (3,6,nb) own partial axes: 1-3 translation, 4-6 rotation
        real(wp), allocatable :: w(:, :, :)        !! (3,n,nb) partial angular velocities omega_pjk
        real(wp), allocatable :: vp(:, :, :)       !! (3,n,nb) partial velocities v_pjk
        real(wp), allocatable :: wd(:, :, :)       !! (3,n,nb) d/dt omega_pjk
        real(wp), allocatable :: vd(:, :, :)       !! (3,n,nb) d/dt v_pjk
        real(wp), allocatable :: a0(:, :)          !! (3,nb) sum_q (dv_pq/dt) xdot_q [m/s^2]
        real(wp), allocatable :: alpha0(:, :)      !! (3,nb) sum_q (domega_pq/dt) xdot_q [rad/s^2]
        real(wp) :: origin(3) = zero               !! reference point of the joint columns: the root's joint point [m]
        real(wp), allocatable :: sj(:, :)          !! (6,n) joint motion column of each coordinate: angular
                                                   !! velocity and velocity of the body point at `origin` per unit rate
    end type kinematics_t

contains

    !> Allocate the kinematic arrays for a built tree.
    pure subroutine kinematics_allocate(tree, kin)
        type(body_tree_t), intent(in) :: tree    !! the built body tree
        type(kinematics_t), intent(out) :: kin   !! arrays allocated for its bodies and coordinates
        integer :: n, nb
        n = max(tree%ndof, 1)
        nb = tree%nbody
        kin%nbody = nb
        kin%ndof = tree%ndof
        allocate (kin%s(3, 3, nb), kin%r(3, nb), kin%v(3, nb), kin%omega(3, nb), kin%joint(3, nb))
        allocate (kin%inertia_r(3, 3, nb), kin%axes(3, 6, nb))
        allocate (kin%w(3, n, nb), kin%vp(3, n, nb), kin%wd(3, n, nb), kin%vd(3, n, nb))
        allocate (kin%a0(3, nb), kin%alpha0(3, nb), kin%sj(6, n))
        kin%sj = zero
        kin%w = zero; kin%vp = zero; kin%wd = zero; kin%vd = zero
        kin%axes = zero
    end subroutine kinematics_allocate

    !> The six relative coordinates of body k and their rates: locked ones at
    !! their reference value with zero rate, active ones from x and xd.
    pure subroutine body_coordinates(tree, k, x, xd, q, qd)
        type(body_tree_t), intent(in) :: tree   !! the body tree
        integer, intent(in) :: k                !! the body
        real(wp), intent(in) :: x(:)            !! active coordinates x_j [m, rad]
        real(wp), intent(in) :: xd(:)           !! their rates xdot_j [m/s, rad/s]
        real(wp), intent(out) :: q(6)           !! body k's translations [m] and Bryant angles [rad] in its parent
        real(wp), intent(out) :: qd(6)          !! their rates [m/s, rad/s]
        integer :: m, j
        do m = 1, 6
            j = tree%dof_index(m, k)
            if (j > 0) then
                q(m) = x(j); qd(m) = xd(j)
            else
                q(m) = tree%q_ref(m, k); qd(m) = zero
            end if
        end do
    end subroutine body_coordinates

    !> Body-level kinematics of the whole tree, parents first, without the
    !! partial-velocity arrays (the fast evaluation paths): transformation
    !! matrices, joint points, mass-centre positions and velocities, angular
    !! velocities, centroidal inertias in R, the velocity-dependent
    !! accelerations a0 and alpha0 (by the recursion of the accelerations
    !! with xddot = 0), and the joint motion columns sj about kin%origin.
    pure subroutine body_kinematics(tree, x, xd, kin)
        type(body_tree_t), intent(in) :: tree      !! the body tree
        real(wp), intent(in) :: x(:)               !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)              !! their time derivatives [m/s, rad/s]
        type(kinematics_t), intent(inout) :: kin   !! allocated; out: the body-level quantities (not w, vp, wd, vd)
        integer :: ik
        do ik = 1, tree%nbody
            call body_step(tree, tree%order(ik), x, xd, kin)
        end do
    end subroutine body_kinematics

    !> One body of the recursion of body_kinematics (its parent done).
    pure subroutine body_step(tree, k, x, xd, kin)
        type(body_tree_t), intent(in) :: tree
        integer, intent(in) :: k
        real(wp), intent(in) :: x(:), xd(:)
        type(kinematics_t), intent(inout) :: kin
        integer :: p, m, j
        real(wp) :: q(6), qd(6), sp(3, 3), omp(3), rp(3), vpar(3), a0p(3), al0p(3), ub(3, 3), u(3, 3)
        real(wp) :: e(3), rho(3), vt(3), ie(3, 3), ud(3, 3), sk(3, 3), ic(3, 3), jp(3), jc(3), rb(3, 3), ict(3, 3)
        real(wp) :: jk(3), om(3), al(3), me(3), jo(3)
        ! fixed-size copies and one product per statement keep the small products inline
        ! (no library calls, no heap temporaries)
        p = tree%parent(k)
        call body_coordinates(tree, k, x, xd, q, qd)
        if (p == 0) then
            sp = zero; sp(1, 1) = 1.0_wp; sp(2, 2) = 1.0_wp; sp(3, 3) = 1.0_wp
            omp = zero; rp = zero; vpar = zero; a0p = zero; al0p = zero
        else
            sp = kin%s(:, :, p); omp = kin%omega(:, p)
            rp = kin%r(:, p); vpar = kin%v(:, p); a0p = kin%a0(:, p); al0p = kin%alpha0(:, p)
        end if
        ! orientation, joint point and mass centre
        rb = bryant_matrix(q(4:6))
        sk = matmul(sp, rb)
        kin%s(:, :, k) = sk
        ub = bryant_axes(q(4:6))
        u = matmul(sp, ub)
        kin%axes(:, 1:3, k) = sp
        kin%axes(:, 4:6, k) = u
        jp = tree%joint_parent(:, k) + q(1:3)
        jk = rp + matmul(sp, jp)
        kin%joint(:, k) = jk
        if (k == tree%order(1)) kin%origin = jk
        jc = tree%joint_child(:, k)
        e = matmul(sk, jc)   ! mass centre -> joint point
        me = -e
        kin%r(:, k) = jk - e
        rho = jk - rp
        ic = tree%inertia(:, :, k)
        ict = matmul(ic, transpose(sk))
        ie = matmul(sk, ict)
        kin%inertia_r(:, :, k) = half*(ie + transpose(ie))
        ! velocities: joint point moves with the parent plus the translations
        om = omp + u(:, 1)*qd(4) + u(:, 2)*qd(5) + u(:, 3)*qd(6)
        kin%omega(:, k) = om
        vt = matmul(sp, qd(1:3))
        kin%v(:, k) = vpar + cross(omp, rho) + vt + cross(om, me)
        ! velocity-dependent accelerations (xddot = 0): d/dt of the above
        ud(:, 1) = cross(omp, u(:, 1))
        ud(:, 2) = cross(omp + u(:, 1)*qd(4), u(:, 2))
        ud(:, 3) = cross(omp + u(:, 1)*qd(4) + u(:, 2)*qd(5), u(:, 3))
        al = al0p + ud(:, 1)*qd(4) + ud(:, 2)*qd(5) + ud(:, 3)*qd(6)
        kin%alpha0(:, k) = al
        kin%a0(:, k) = a0p + cross(al0p, rho) + cross(omp, cross(omp, rho)) + 2.0_wp*cross(omp, vt) &
                       + cross(al, me) + cross(om, cross(om, me))
        ! joint motion columns about the origin: (angular; linear at the origin)
        jo = jk - kin%origin
        do m = 1, 6
            j = tree%dof_index(m, k)
            if (j == 0) cycle
            if (m <= 3) then
                kin%sj(1:3, j) = zero
                kin%sj(4:6, j) = sp(:, m)
            else
                kin%sj(1:3, j) = u(:, m - 3)
                kin%sj(4:6, j) = cross(jo, u(:, m - 3))
            end if
        end do
    end subroutine body_step

    !> Recursive kinematics of the paper (eqs 15-16 and their derivatives):
    !! the body-level quantities of body_kinematics, and for each body,
    !! parents first, the partial velocities v_pjk and partial angular
    !! velocities omega_pjk and their time derivatives, inherited from the
    !! parent plus the body's own coordinates. (The faithful path; a0 and
    !! alpha0 equal sum_q (dv_pq/dt) xdot_q and sum_q (domega_pq/dt) xdot_q.)
    pure subroutine partial_velocities(tree, x, xd, kin)
        type(body_tree_t), intent(in) :: tree      !! the body tree
        real(wp), intent(in) :: x(:)               !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)              !! their time derivatives [m/s, rad/s]
        type(kinematics_t), intent(inout) :: kin   !! allocated; out: body quantities, v_pjk, omega_pjk, d/dt of both
        integer :: ik, k, p, jj, j, m, jm
        real(wp) :: q(6), qd(6), sp(3, 3), omp(3), u(3, 3), ud(3, 3), e(3), d(3), dv(3), ea(3)

        do ik = 1, tree%nbody
            k = tree%order(ik)
            p = tree%parent(k)
            call body_step(tree, k, x, xd, kin)
            call body_coordinates(tree, k, x, xd, q, qd)
            sp = kin%axes(:, 1:3, k)
            u = kin%axes(:, 4:6, k)
            e = kin%joint(:, k) - kin%r(:, k)
            if (p == 0) then
                omp = zero; d = kin%r(:, k); dv = kin%v(:, k)
            else
                omp = kin%omega(:, p); d = kin%r(:, k) - kin%r(:, p); dv = kin%v(:, k) - kin%v(:, p)
            end if
            ! partial (angular) velocities and their derivatives: inherited from the parent ...
            if (p /= 0) then
                do jj = 1, tree%chain_len(p)
                    j = tree%chain(jj, p)
                    kin%w(:, j, k) = kin%w(:, j, p)
                    kin%vp(:, j, k) = kin%vp(:, j, p) + cross(kin%w(:, j, p), d)
                    kin%wd(:, j, k) = kin%wd(:, j, p)
                    kin%vd(:, j, k) = kin%vd(:, j, p) + cross(kin%wd(:, j, p), d) + cross(kin%w(:, j, p), dv)
                end do
            end if
            ! ... and the body's own coordinates
            ud(:, 1) = cross(omp, u(:, 1))
            ud(:, 2) = cross(omp + u(:, 1)*qd(4), u(:, 2))
            ud(:, 3) = cross(omp + u(:, 1)*qd(4) + u(:, 2)*qd(5), u(:, 3))
            ea = cross(kin%omega(:, k), -e)
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j == 0) cycle
                if (m <= 3) then
                    kin%w(:, j, k) = zero
                    kin%vp(:, j, k) = sp(:, m)
                    kin%wd(:, j, k) = zero
                    kin%vd(:, j, k) = cross(omp, sp(:, m))
                else
                    jm = m - 3
                    kin%w(:, j, k) = u(:, jm)
                    kin%vp(:, j, k) = cross(u(:, jm), -e)
                    kin%wd(:, j, k) = ud(:, jm)
                    kin%vd(:, j, k) = cross(ud(:, jm), -e) + cross(u(:, jm), ea)
                end if
            end do
        end do
    end subroutine partial_velocities

    !> Mass-centre and angular accelerations of every body for given xddot:
    !! a_p = a0_p + v_pj xddot_j, alpha_p = alpha0_p + omega_pj xddot_j,
    !! summed recursively as the spatial acceleration sj xddot of each
    !! body's chain (no partial-velocity arrays needed).
    pure subroutine body_accelerations(tree, kin, xdd, acc, alpha)
        type(body_tree_t), intent(in) :: tree   !! the body tree
        type(kinematics_t), intent(in) :: kin   !! from body_kinematics or partial_velocities at the same state
        real(wp), intent(in) :: xdd(:)          !! coordinate accelerations xddot_j [m/s^2, rad/s^2]
        real(wp), intent(out) :: acc(:, :)      !! (3, nb) mass-centre accelerations in R [m/s^2]
        real(wp), intent(out) :: alpha(:, :)    !! (3, nb) angular accelerations in R [rad/s^2]
        real(wp) :: sa(6, tree%nbody)
        integer :: ik, k, m, j
        do ik = 1, tree%nbody
            k = tree%order(ik)
            if (tree%parent(k) == 0) then
                sa(:, k) = zero
            else
                sa(:, k) = sa(:, tree%parent(k))
            end if
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j > 0) sa(:, k) = sa(:, k) + kin%sj(:, j)*xdd(j)
            end do
            alpha(:, k) = kin%alpha0(:, k) + sa(1:3, k)
            acc(:, k) = kin%a0(:, k) + sa(4:6, k) + cross(sa(1:3, k), kin%r(:, k) - kin%origin)
        end do
    end subroutine body_accelerations

    !> Kinetic energy sum_p (m_p v_p.v_p + omega_p.I_p omega_p)/2 from body velocities.
    pure real(wp) function kinetic_energy(tree, kin) result(t)
        type(body_tree_t), intent(in) :: tree   !! masses of the bodies
        type(kinematics_t), intent(in) :: kin   !! velocities, angular velocities, inertias in R
        integer :: k
        real(wp) :: ir(3, 3), om(3)
        t = zero
        do k = 1, tree%nbody
            ir = kin%inertia_r(:, :, k)     ! fixed-size copies keep the product inline
            om = kin%omega(:, k)
            t = t + half*tree%mass(k)*dot_product(kin%v(:, k), kin%v(:, k)) &
                + half*dot_product(om, matmul(ir, om))
        end do
    end function kinetic_energy

    !> Total linear momentum sum_p m_p v_p.
    pure function linear_momentum(tree, kin) result(pl)
        type(body_tree_t), intent(in) :: tree   !! masses of the bodies
        type(kinematics_t), intent(in) :: kin   !! mass-centre velocities
        real(wp) :: pl(3)
        integer :: k
        pl = zero
        do k = 1, tree%nbody
            pl = pl + tree%mass(k)*kin%v(:, k)
        end do
    end function linear_momentum

    !> Total angular momentum about the origin of R.
    pure function angular_momentum(tree, kin) result(h)
        type(body_tree_t), intent(in) :: tree   !! masses of the bodies
        type(kinematics_t), intent(in) :: kin   !! positions, velocities, angular velocities, inertias in R
        real(wp) :: h(3)
        integer :: k
        h = zero
        do k = 1, tree%nbody
            h = h + tree%mass(k)*cross(kin%r(:, k), kin%v(:, k)) &
                + matmul(kin%inertia_r(:, :, k), kin%omega(:, k))
        end do
    end function angular_momentum

end module hn_kinematics
