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

    public :: kinematics_t, kinematics_allocate, partial_velocities
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
    end type kinematics_t

contains

    !> Allocate the kinematic arrays for a built tree.
    pure subroutine kinematics_allocate(tree, kin)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(out) :: kin
        integer :: n, nb
        n = max(tree%ndof, 1)
        nb = tree%nbody
        kin%nbody = nb
        kin%ndof = tree%ndof
        allocate (kin%s(3, 3, nb), kin%r(3, nb), kin%v(3, nb), kin%omega(3, nb), kin%joint(3, nb))
        allocate (kin%inertia_r(3, 3, nb), kin%axes(3, 6, nb))
        allocate (kin%w(3, n, nb), kin%vp(3, n, nb), kin%wd(3, n, nb), kin%vd(3, n, nb))
        allocate (kin%a0(3, nb), kin%alpha0(3, nb))
        kin%w = zero; kin%vp = zero; kin%wd = zero; kin%vd = zero
        kin%axes = zero
    end subroutine kinematics_allocate

    !> The six relative coordinates of body k and their rates: locked ones at
    !! their reference value with zero rate, active ones from x and xd.
    pure subroutine body_coordinates(tree, k, x, xd, q, qd)
        type(body_tree_t), intent(in) :: tree
        integer, intent(in) :: k
        real(wp), intent(in) :: x(:), xd(:)
        real(wp), intent(out) :: q(6), qd(6)
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

    !> Recursive kinematics (eqs 15-16 and their derivatives): for each body,
    !! parents first, the transformation matrix, mass-centre position and
    !! velocity, angular velocity, the partial velocities v_pjk and partial
    !! angular velocities omega_pjk, their time derivatives, and the
    !! velocity-dependent accelerations a0 = (dv_pq/dt) xdot_q and
    !! alpha0 = (domega_pq/dt) xdot_q.
    pure subroutine partial_velocities(tree, x, xd, kin)
        type(body_tree_t), intent(in) :: tree
        real(wp), intent(in) :: x(:)     !! active coordinates
        real(wp), intent(in) :: xd(:)    !! their time derivatives
        type(kinematics_t), intent(inout) :: kin
        integer :: ik, k, p, jj, j, m, jm
        real(wp) :: q(6), qd(6), sp(3, 3), omp(3), rp(3), vpar(3), ub(3, 3), u(3, 3), ud(3, 3)
        real(wp) :: e(3), d(3), dv(3), wrel(3), ea(3), ie(3, 3)

        do ik = 1, tree%nbody
            k = tree%order(ik)
            p = tree%parent(k)
            call body_coordinates(tree, k, x, xd, q, qd)
            if (p == 0) then
                sp = zero; sp(1, 1) = 1.0_wp; sp(2, 2) = 1.0_wp; sp(3, 3) = 1.0_wp
                omp = zero; rp = zero; vpar = zero
            else
                sp = kin%s(:, :, p); omp = kin%omega(:, p)
                rp = kin%r(:, p); vpar = kin%v(:, p)
            end if

            ! orientation, joint point and mass centre
            kin%s(:, :, k) = matmul(sp, bryant_matrix(q(4:6)))
            ub = bryant_axes(q(4:6))
            u = matmul(sp, ub)
            kin%axes(:, 1:3, k) = sp
            kin%axes(:, 4:6, k) = u
            kin%joint(:, k) = rp + matmul(sp, tree%joint_parent(:, k) + q(1:3))
            e = matmul(kin%s(:, :, k), tree%joint_child(:, k))   ! mass centre -> joint point
            kin%r(:, k) = kin%joint(:, k) - e
            d = kin%r(:, k) - rp
            wrel = u(:, 1)*qd(4) + u(:, 2)*qd(5) + u(:, 3)*qd(6)
            kin%omega(:, k) = omp + wrel
            ie = matmul(kin%s(:, :, k), matmul(tree%inertia(:, :, k), transpose(kin%s(:, :, k))))
            kin%inertia_r(:, :, k) = half*(ie + transpose(ie))

            ! partial (angular) velocities: inherited from the parent ...
            kin%v(:, k) = zero
            if (p /= 0) then
                do jj = 1, tree%chain_len(p)
                    j = tree%chain(jj, p)
                    kin%w(:, j, k) = kin%w(:, j, p)
                    kin%vp(:, j, k) = kin%vp(:, j, p) + cross(kin%w(:, j, p), d)
                end do
            end if
            ! ... and the body's own coordinates
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j == 0) cycle
                if (m <= 3) then
                    kin%w(:, j, k) = zero
                    kin%vp(:, j, k) = sp(:, m)
                else
                    kin%w(:, j, k) = u(:, m - 3)
                    kin%vp(:, j, k) = cross(u(:, m - 3), -e)
                end if
            end do
            do jj = 1, tree%chain_len(k)
                j = tree%chain(jj, k)
                kin%v(:, k) = kin%v(:, k) + kin%vp(:, j, k)*xd(j)
            end do

            ! time derivatives of the partials
            dv = kin%v(:, k) - vpar
            if (p /= 0) then
                do jj = 1, tree%chain_len(p)
                    j = tree%chain(jj, p)
                    kin%wd(:, j, k) = kin%wd(:, j, p)
                    kin%vd(:, j, k) = kin%vd(:, j, p) + cross(kin%wd(:, j, p), d) + cross(kin%w(:, j, p), dv)
                end do
            end if
            ud(:, 1) = cross(omp, u(:, 1))
            ud(:, 2) = cross(omp + u(:, 1)*qd(4), u(:, 2))
            ud(:, 3) = cross(omp + u(:, 1)*qd(4) + u(:, 2)*qd(5), u(:, 3))
            ea = cross(kin%omega(:, k), -e)        ! d/dt of (mass centre -> ... ) -e
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j == 0) cycle
                if (m <= 3) then
                    kin%wd(:, j, k) = zero
                    kin%vd(:, j, k) = cross(omp, sp(:, m))
                else
                    jm = m - 3
                    kin%wd(:, j, k) = ud(:, jm)
                    kin%vd(:, j, k) = cross(ud(:, jm), -e) + cross(u(:, jm), ea)
                end if
            end do
            kin%a0(:, k) = zero
            kin%alpha0(:, k) = zero
            do jj = 1, tree%chain_len(k)
                j = tree%chain(jj, k)
                kin%a0(:, k) = kin%a0(:, k) + kin%vd(:, j, k)*xd(j)
                kin%alpha0(:, k) = kin%alpha0(:, k) + kin%wd(:, j, k)*xd(j)
            end do
        end do
    end subroutine partial_velocities

    !> Mass-centre and angular accelerations of every body for given xddot:
    !! a_p = a0_p + v_pj xddot_j, alpha_p = alpha0_p + omega_pj xddot_j.
    pure subroutine body_accelerations(tree, kin, xdd, acc, alpha)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        real(wp), intent(in) :: xdd(:)
        real(wp), intent(out) :: acc(:, :), alpha(:, :)
        integer :: k, jj, j
        do k = 1, tree%nbody
            acc(:, k) = kin%a0(:, k)
            alpha(:, k) = kin%alpha0(:, k)
            do jj = 1, tree%chain_len(k)
                j = tree%chain(jj, k)
                acc(:, k) = acc(:, k) + kin%vp(:, j, k)*xdd(j)
                alpha(:, k) = alpha(:, k) + kin%w(:, j, k)*xdd(j)
            end do
        end do
    end subroutine body_accelerations

    !> Kinetic energy sum_p (m_p v_p.v_p + omega_p.I_p omega_p)/2 from body velocities.
    pure real(wp) function kinetic_energy(tree, kin) result(t)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        integer :: k
        t = zero
        do k = 1, tree%nbody
            t = t + half*tree%mass(k)*dot_product(kin%v(:, k), kin%v(:, k)) &
                + half*dot_product(kin%omega(:, k), matmul(kin%inertia_r(:, :, k), kin%omega(:, k)))
        end do
    end function kinetic_energy

    !> Total linear momentum sum_p m_p v_p.
    pure function linear_momentum(tree, kin) result(pl)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        real(wp) :: pl(3)
        integer :: k
        pl = zero
        do k = 1, tree%nbody
            pl = pl + tree%mass(k)*kin%v(:, k)
        end do
    end function linear_momentum

    !> Total angular momentum about the origin of R.
    pure function angular_momentum(tree, kin) result(h)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        real(wp) :: h(3)
        integer :: k
        h = zero
        do k = 1, tree%nbody
            h = h + tree%mass(k)*cross(kin%r(:, k), kin%v(:, k)) &
                + matmul(kin%inertia_r(:, :, k), kin%omega(:, k))
        end do
    end function angular_momentum

end module hn_kinematics
