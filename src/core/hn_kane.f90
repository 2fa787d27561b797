!> Kane's equations in the paper's form a_ij xddot_j = f_i (eq 14):
!! a_ij (eq 17), the generalized active forces F_i (eq 19) and f_i (eq 18).
module hn_kane
    use hn_kinds, only: wp, zero
    use hn_status, only: stat_ok, stat_gimbal
    use hn_rotation, only: cross
    use hn_tree, only: body_tree_t
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    implicit none
    private

    public :: a_ij, generalized_active_forces, f_i, equivalent_body_loads

    !> |det| of a body's three Bryant axes below which they are taken as
    !! dependent (cos(beta) = 0: the gimbal singularity).
    real(wp), parameter :: axes_det_min = 1.0e-12_wp

contains

    !> Generalized mass matrix (eq 17), the coefficients of the equations of
    !! motion a_ij xddot_j = f_i (eq 14):
    !! a_ij = sum_p m_p v_pik v_pjk + omega_pik I_pkn omega_pjn.
    !! Only pairs within one body's chain contribute. With I_p = (S L)(S L)^T
    !! (L the Cholesky factor of the body-frame inertia) each body adds
    !! B^T B, B = [sqrt(m_p) v_pj ; (S L)^T omega_pj] (6 x chain length),
    !! which is how it is computed: six rank-one updates on the chain block.
    pure subroutine a_ij(tree, kin, a)
        type(body_tree_t), intent(in) :: tree   !! masses, inertia factors and chains of the bodies
        type(kinematics_t), intent(in) :: kin   !! v_pjk, omega_pjk and S from partial_velocities
        real(wp), intent(out) :: a(:, :)        !! (n,n) symmetric positive definite
        integer :: p, ii, jj, j, nc, k, c0
        real(wp) :: sm, sl(3, 3), b(size(a, 1), 6), col(size(a, 1))
        a = zero
        do p = 1, tree%nbody
            nc = tree%chain_len(p)
            if (nc == 0) cycle
            sm = sqrt(tree%mass(p))
            sl = matmul(kin%s(:, :, p), tree%inertia_factor(:, :, p))
            do jj = 1, nc
                j = tree%chain(jj, p)
                b(jj, 1:3) = sm*kin%vp(:, j, p)
                b(jj, 4:6) = matmul(kin%w(:, j, p), sl)
            end do
            c0 = tree%chain(1, p)
            do jj = 1, nc
                col(1:jj) = b(1:jj, 1)*b(jj, 1)
                do k = 2, 6
                    col(1:jj) = col(1:jj) + b(1:jj, k)*b(jj, k)
                end do
                j = tree%chain(jj, p)
                if (tree%chain_contiguous(p)) then
                    a(c0:c0 + jj - 1, j) = a(c0:c0 + jj - 1, j) + col(1:jj)
                else
                    do ii = 1, jj
                        a(tree%chain(ii, p), j) = a(tree%chain(ii, p), j) + col(ii)
                    end do
                end if
            end do
        end do
        do j = 1, size(a, 2)
            do ii = j + 1, size(a, 1)
                a(ii, j) = a(j, ii)
            end do
        end do
    end subroutine a_ij

    !> Generalized active forces (eq 19): F_i = v_pik F_pk + omega_pik M_pk
    !! plus the generalized forces applied directly to coordinates.
    pure subroutine generalized_active_forces(tree, kin, loads, fa)
        type(body_tree_t), intent(in) :: tree     !! chains of the bodies
        type(kinematics_t), intent(in) :: kin     !! v_pjk and omega_pjk from partial_velocities
        type(body_loads_t), intent(in) :: loads   !! body forces F_pk [N], moments M_pk [N m], generalized forces q
        real(wp), intent(out) :: fa(:)            !! (n) F_i [N or N m]
        call project_on_partials(tree, kin, loads%force, loads%moment, fa)
        fa = fa + loads%q(1:size(fa))
    end subroutine generalized_active_forces

    !> Right-hand side (eq 18): f_i = F_i - sum_p [ m_p v_pik (dv_pqk/dt) xdot_q
    !!   + omega_pik ( I_pkn (domega_pqn/dt) xdot_q + (omega_p x I_p omega_p)_k ) ].
    pure subroutine f_i(tree, kin, loads, f)
        type(body_tree_t), intent(in) :: tree     !! masses and chains of the bodies
        type(kinematics_t), intent(in) :: kin     !! v_pjk, omega_pjk, inertias in R and the velocity terms a0, alpha0
        type(body_loads_t), intent(in) :: loads   !! body forces F_pk [N], moments M_pk [N m], generalized forces q
        real(wp), intent(out) :: f(:)             !! (n) f_i [N or N m]
        real(wp) :: fstar(3, tree%nbody), mstar(3, tree%nbody), iw(3)
        integer :: p
        do p = 1, tree%nbody
            iw = matmul(kin%inertia_r(:, :, p), kin%omega(:, p))
            fstar(:, p) = loads%force(:, p) - tree%mass(p)*kin%a0(:, p)
            mstar(:, p) = loads%moment(:, p) - matmul(kin%inertia_r(:, :, p), kin%alpha0(:, p)) &
                          - cross(kin%omega(:, p), iw)
        end do
        call project_on_partials(tree, kin, fstar, mstar, f)
        f = f + loads%q(1:size(f))
    end subroutine f_i

    !> Resultant force and moment on every body equivalent to the body loads
    !! plus the generalized forces q on coordinates: q on the translations of
    !! body k becomes a force pair at its joint point, q on its rotations a
    !! couple pair M with u_m . M = q_m (u_m the Bryant axes; M has no
    !! component along a locked axis). stat = stat_gimbal when the Bryant
    !! axes of a body (bad_body) are singular (cos(beta) = 0) and q acts on
    !! its rotations.
    pure subroutine equivalent_body_loads(tree, kin, loads, force, moment, stat, bad_body)
        type(body_tree_t), intent(in) :: tree     !! parents and coordinate numbering of the bodies
        type(kinematics_t), intent(in) :: kin     !! axes, joint points and mass centres
        type(body_loads_t), intent(in) :: loads   !! body loads and generalized forces q on coordinates
        real(wp), intent(out) :: force(:, :)      !! (3, nb) resultant force through each mass centre in R [N]
        real(wp), intent(out) :: moment(:, :)     !! (3, nb) resultant moment about each mass centre in R [N m]
        integer, intent(out) :: stat              !! stat_ok, or stat_gimbal (Bryant axes of bad_body singular)
        integer, intent(out) :: bad_body          !! the body whose axes are singular (0: none)
        integer :: k, p, m, j
        real(wp) :: ft(3), qr(3), u(3, 3), c(3), det, adj(3, 3)
        stat = stat_ok
        bad_body = 0
        force = loads%force
        moment = loads%moment
        do k = 1, tree%nbody
            p = tree%parent(k)
            ft = zero; qr = zero
            do m = 1, 6
                j = tree%dof_index(m, k)
                if (j == 0) cycle
                if (m <= 3) then
                    ft = ft + kin%axes(:, m, k)*loads%q(j)
                else
                    qr(m - 3) = loads%q(j)
                end if
            end do
            if (any(ft /= zero)) then
                force(:, k) = force(:, k) + ft
                moment(:, k) = moment(:, k) + cross(kin%joint(:, k) - kin%r(:, k), ft)
                if (p > 0) then
                    force(:, p) = force(:, p) - ft
                    moment(:, p) = moment(:, p) - cross(kin%joint(:, k) - kin%r(:, p), ft)
                end if
            end if
            if (any(qr /= zero)) then
                ! solve u^T c = qr (zero component along the axis of a locked rotation)
                u = kin%axes(:, 4:6, k)
                adj(:, 1) = cross(u(:, 2), u(:, 3))
                adj(:, 2) = cross(u(:, 3), u(:, 1))
                adj(:, 3) = cross(u(:, 1), u(:, 2))
                det = dot_product(u(:, 1), adj(:, 1))
                if (abs(det) < axes_det_min) then
                    stat = stat_gimbal
                    bad_body = k
                    cycle
                end if
                c = matmul(adj, qr)/det
                moment(:, k) = moment(:, k) + c
                if (p > 0) moment(:, p) = moment(:, p) - c
            end if
        end do
    end subroutine equivalent_body_loads

    !> g_i = v_pik F_pk + omega_pik M_pk for per-body vectors F, M.
    pure subroutine project_on_partials(tree, kin, force, moment, g)
        type(body_tree_t), intent(in) :: tree
        type(kinematics_t), intent(in) :: kin
        real(wp), intent(in) :: force(:, :), moment(:, :)
        real(wp), intent(out) :: g(:)
        integer :: p, ii, i
        g = zero
        do p = 1, tree%nbody
            do ii = 1, tree%chain_len(p)
                i = tree%chain(ii, p)
                g(i) = g(i) + dot_product(kin%vp(:, i, p), force(:, p)) &
                       + dot_product(kin%w(:, i, p), moment(:, p))
            end do
        end do
    end subroutine project_on_partials

end module hn_kane
