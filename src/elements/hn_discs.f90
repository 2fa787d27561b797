!> Intervertebral discs (paper eqs 1-9): a short Timoshenko beam between a
!! plate on the lower body and a plate on the upper body.
!!
!! Deformations q = (u, theta) of the upper plate relative to the lower one,
!! in the lower plate frame L, measured from the neutral configuration:
!! u = L^T (P_u - P_l) - d0 (shear u1, u2; axial u3) and theta the rotation
!! vector of L^T U (bending theta1, theta2; torsion theta3). The stress
!! resultants s = K q + C qdot:
!!   axial    P = (A/h)(d1 u3 + d2 u3')                      (eq 1)
!!   shear and bending in each plane, Timoshenko beam with
!!   Phi = 12 E I k / (G A h^2), E = d1                       (eqs 2-6, 8-9)
!!     [V; M] = E I / (h^3 (1 + Phi)) [12, -6h; -6h, (4 + Phi) h^2] [w; psi]
!!   torsion  T = G J theta3 / h                              (eq 7)
!! and C = (d2/d1) K in the axial mode (eq 1) and C = (d2b/d1) K in shear,
!! bending and torsion (d2b = d2 unless the deck gives it: the same
!! two-parameter viscoelastic law in every mode). The rotations may carry
!! their own viscous modulus d2r (bending and torsion; d2r = d2b unless
!! given): with the retardation times ts = d2b/d1 and tr = d2r/d1,
!!   C = min(ts, tr) K + (tr - ts)+ K_rr + (ts - tr)+ K_uu
!! (K_rr, K_uu the rotational and translational principal blocks of K), a
!! sum of positive semi-definite terms: the rotations damped with tr, the
!! shear with ts, whichever is the larger.
!! In tension (u3 > 0) the axial stiffness is ft (A/h) d1, ft the deck's
!! tension fraction (default 1: the paper's linear law); the damping stays
!! C in either direction.
!! The loads on the bodies are the work-conjugates of q: the element stores
!! U = q^T K q / 2 - (1 - ft) K33 u3^2 / 2 (the last term in tension only)
!! exactly and dissipates qdot^T C qdot.
module hn_discs
    use hn_kinds, only: wp, zero, one, half
    use hn_rotation, only: cross, skew, rot_y, rotation_vector, norm3
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t, add_force_pair
    implicit none
    private

    public :: disc_t, disc_stiffness, disc_set_reference, disc_deformation, disc_resultants
    public :: apply_disc, disc_energy, inv_left_jacobian

    !> One disc and its constants.
    type :: disc_t
        character(len=12) :: name = ''
        integer :: body_a = 0, body_b = 0     !! lower and upper body
        real(wp) :: pa(3) = zero              !! lower plate centre, lower body frame from its mass centre [m]
        real(wp) :: pb(3) = zero              !! upper plate centre, upper body frame [m]
        real(wp) :: tilt = zero               !! plate frame rotation about the lower body's y axis [rad]
        real(wp) :: area = zero               !! A [m^2]
        real(wp) :: h = zero                  !! thickness [m]
        real(wp) :: d1 = zero                 !! elastic modulus E [Pa]
        real(wp) :: d2 = zero                 !! viscous modulus, axial [Pa s]
        real(wp) :: d2b = -one                !! viscous modulus of shear, bending and torsion [Pa s]; < 0: d2
        real(wp) :: d2r = -one                !! viscous modulus of bending and torsion alone [Pa s]; < 0: d2b's
        real(wp) :: ft = one                  !! axial stiffness in tension as a fraction of d1's [-]
        real(wp) :: g = zero                  !! shear modulus [Pa]
        real(wp) :: ix = zero, iy = zero      !! second moments of area about plate x, y [m^4]
        real(wp) :: j = zero                  !! torsion constant [m^4]
        real(wp) :: kshear = 1.2_wp           !! shear shape factor k (1.2 rectangle, 10/9 circle)
        real(wp) :: ra(3, 3) = reshape([one, zero, zero, zero, one, zero, zero, zero, one], [3, 3]) !! plate frame in lower body
        real(wp) :: rb(3, 3) = reshape([one, zero, zero, zero, one, zero, zero, zero, one], [3, 3]) !! plate frame in upper body
        real(wp) :: d0(3) = zero              !! neutral offset of the plates in L [m]
        real(wp) :: k(6, 6) = zero            !! stiffness
        real(wp) :: c(6, 6) = zero            !! damping
    end type disc_t

contains

    !> Stiffness K of the disc (eqs 1-9), ordered (u1, u2, u3, theta1, theta2, theta3).
    pure function disc_stiffness(d) result(k)
        type(disc_t), intent(in) :: d            !! the disc
        real(wp) :: k(6, 6)
        real(wp) :: phi, kb
        k = zero
        ! x-z plane: deflection u1, slope psi = theta2
        phi = 12*d%d1*d%iy*d%kshear/(d%g*d%area*d%h**2)
        kb = d%d1*d%iy/(d%h**3*(one + phi))
        k(1, 1) = 12*kb
        k(1, 5) = -6*d%h*kb
        k(5, 1) = k(1, 5)
        k(5, 5) = (4 + phi)*d%h**2*kb
        ! y-z plane: deflection u2, slope psi = -theta1
        phi = 12*d%d1*d%ix*d%kshear/(d%g*d%area*d%h**2)
        kb = d%d1*d%ix/(d%h**3*(one + phi))
        k(2, 2) = 12*kb
        k(2, 4) = 6*d%h*kb
        k(4, 2) = k(2, 4)
        k(4, 4) = (4 + phi)*d%h**2*kb
        ! axial and torsion
        k(3, 3) = d%d1*d%area/d%h
        k(6, 6) = d%g*d%j/d%h
    end function disc_stiffness

    !> Fix the plate frames and neutral offset from the kinematics of the
    !! neutral configuration, and form K and C.
    pure subroutine disc_set_reference(d, kin)
        type(disc_t), intent(inout) :: d         !! the disc; out: its plate frames, neutral offset, K and C
        type(kinematics_t), intent(in) :: kin    !! kinematics in the neutral configuration
        real(wp) :: sl(3, 3), su(3, 3), plo(3), pup(3)
        d%ra = rot_y(d%tilt)
        call plates(d, kin, sl, su, plo, pup)
        sl = matmul(sl, d%ra)                  ! the lower plate frame L = S_a ra, as disc_deformation uses
        d%rb = matmul(transpose(su), sl)
        d%d0 = matmul(transpose(sl), pup - plo)
        d%k = disc_stiffness(d)
        d%c = disc_damping(d%k, disc_d2b(d)/d%d1, disc_d2r(d)/d%d1)
        d%c(3, 3) = (d%d2/d%d1)*d%k(3, 3)     ! axial (eq 1)
    end subroutine disc_set_reference

    !> The damping of shear, bending and torsion from the stiffness K and the
    !! retardation times of the shear (ts) and of the rotations (tr):
    !! min(ts, tr) K plus the excess of either on its own principal block of
    !! K (symmetric and positive semi-definite with K). The axial entry is
    !! the caller's (K has no axial coupling).
    pure function disc_damping(k, ts, tr) result(c)
        real(wp), intent(in) :: k(6, 6)         !! the disc's stiffness (disc_stiffness)
        real(wp), intent(in) :: ts               !! retardation time of the shear, d2b/d1 [s]
        real(wp), intent(in) :: tr               !! retardation time of bending and torsion, d2r/d1 [s]
        real(wp) :: c(6, 6)
        c = min(ts, tr)*k
        c(4:6, 4:6) = c(4:6, 4:6) + max(zero, tr - ts)*k(4:6, 4:6)
        c(1:3, 1:3) = c(1:3, 1:3) + max(zero, ts - tr)*k(1:3, 1:3)
    end function disc_damping

    !> The viscous modulus of shear, bending and torsion: d2b, or d2 where the deck gives none.
    elemental function disc_d2b(d) result(v)
        type(disc_t), intent(in) :: d            !! the disc
        real(wp) :: v                            !! [Pa s]
        v = merge(d%d2b, d%d2, d%d2b >= zero)
    end function disc_d2b

    !> The viscous modulus of bending and torsion: d2r, or disc_d2b where the deck gives none.
    elemental function disc_d2r(d) result(v)
        type(disc_t), intent(in) :: d            !! the disc
        real(wp) :: v                            !! [Pa s]
        v = merge(d%d2r, disc_d2b(d), d%d2r >= zero)
    end function disc_d2r

    !> Body frames and plate centres (R) of the two bodies.
    pure subroutine plates(d, kin, sa, sb, plo, pup)
        type(disc_t), intent(in) :: d
        type(kinematics_t), intent(in) :: kin
        real(wp), intent(out) :: sa(3, 3), sb(3, 3), plo(3), pup(3)
        sa = kin%s(:, :, d%body_a)
        sb = kin%s(:, :, d%body_b)
        plo = kin%r(:, d%body_a) + matmul(sa, d%pa)
        pup = kin%r(:, d%body_b) + matmul(sb, d%pb)
    end subroutine plates

    !> J_l(theta)^-1 of the rotation vector: thetadot = J^-1 omega, omega the
    !! left (spatial) angular velocity of exp(skew(theta)).
    pure function inv_left_jacobian(th) result(m)
        real(wp), intent(in) :: th(3)            !! rotation vector [rad]
        real(wp) :: m(3, 3), t, a, w(3, 3)
        integer :: i
        t = norm3(th)
        w = skew(th)
        if (t < 1.0e-4_wp) then
            a = one/12 + t**2/720
        else
            a = (one - half*t*cos(half*t)/sin(half*t))/t**2
        end if
        m = -half*w + a*matmul(w, w)
        do i = 1, 3
            m(i, i) = m(i, i) + one
        end do
    end function inv_left_jacobian

    !> Deformations q and rates qd of the disc, the lower plate frame L (R)
    !! and the upper plate centre (R) where the loads act.
    pure subroutine disc_deformation(d, kin, q, qd, l, pup, jinv)
        type(disc_t), intent(in) :: d            !! the disc
        type(kinematics_t), intent(in) :: kin    !! kinematics of the tree
        real(wp), intent(out) :: q(6)            !! deformations: u1, u2, u3 [m], theta1-3 [rad]
        real(wp), intent(out) :: qd(6)           !! their rates [m/s, rad/s]
        real(wp), intent(out) :: l(3, 3)         !! lower plate frame L in R
        real(wp), intent(out) :: pup(3)          !! upper plate centre in R [m]
        real(wp), intent(out), optional :: jinv(3, 3) !! J_l(theta)^-1 of the rotation q(4:6) (inv_left_jacobian)
        real(wp) :: sa(3, 3), sb(3, 3), plo(3), rel(3), vrel(3), wa(3), wb(3), lt(3, 3), ub(3, 3), lu(3, 3)
        real(wp) :: ji(3, 3), wl(3)
        ! one product per statement on fixed-size arrays: inline, no heap temporaries
        call plates(d, kin, sa, sb, plo, pup)
        l = matmul(sa, d%ra)
        lt = transpose(l)
        rel = pup - plo
        q(1:3) = matmul(lt, rel) - d%d0
        ub = matmul(sb, d%rb)
        lu = matmul(lt, ub)
        q(4:6) = rotation_vector(lu)
        wa = kin%omega(:, d%body_a)
        wb = kin%omega(:, d%body_b)
        vrel = kin%v(:, d%body_b) + cross(wb, pup - kin%r(:, d%body_b)) &
               - kin%v(:, d%body_a) - cross(wa, plo - kin%r(:, d%body_a)) - cross(wa, rel)
        qd(1:3) = matmul(lt, vrel)
        ji = inv_left_jacobian(q(4:6))
        wl = matmul(lt, wb - wa)
        qd(4:6) = matmul(ji, wl)
        if (present(jinv)) jinv = ji
    end subroutine disc_deformation

    !> Stress resultants s = K q + C qd: shear forces, axial force (tension
    !! positive), bending moments and torque conjugate to q; in tension the
    !! axial stiffness is ft K33.
    pure function disc_resultants(d, q, qd) result(s)
        type(disc_t), intent(in) :: d            !! the disc
        real(wp), intent(in) :: q(6)             !! deformations [m, rad]
        real(wp), intent(in) :: qd(6)            !! their rates [m/s, rad/s]
        real(wp) :: s(6)
        s = matmul(d%k, q) + matmul(d%c, qd)
        if (q(3) > zero) s(3) = s(3) - (one - d%ft)*d%k(3, 3)*q(3)
    end function disc_resultants

    !> Elastic energy q^T K q / 2, less (1 - ft) K33 u3^2 / 2 in tension.
    pure real(wp) function disc_energy(d, q) result(u)
        type(disc_t), intent(in) :: d            !! the disc
        real(wp), intent(in) :: q(6)             !! deformations [m, rad]
        u = half*dot_product(q, matmul(d%k, q))
        if (q(3) > zero) u = u - half*(one - d%ft)*d%k(3, 3)*q(3)**2
    end function disc_energy

    !> Add the disc loads to both bodies; returns the resultants s, the
    !! stored energy u = q^T K q / 2 and the dissipated power qd^T C qd.
    pure subroutine apply_disc(d, kin, loads, s, u, pdiss)
        type(disc_t), intent(in) :: d            !! the disc
        type(kinematics_t), intent(in) :: kin    !! kinematics of the tree
        type(body_loads_t), intent(inout) :: loads !! body loads, the disc's added
        real(wp), intent(out) :: s(6)            !! resultants: shear, axial [N], bending, torque [N m]
        real(wp), intent(out) :: u       !! elastic energy [J]
        real(wp), intent(out) :: pdiss   !! dissipated power [W]
        real(wp) :: q(6), qd(6), l(3, 3), pup(3), f(3), c(3), jt(3, 3), jinv(3, 3), m(3)
        call disc_deformation(d, kin, q, qd, l, pup, jinv)
        s = disc_resultants(d, q, qd)
        u = disc_energy(d, q)
        pdiss = dot_product(qd, matmul(d%c, qd))
        f = -matmul(l, s(1:3))
        jt = transpose(jinv)
        m = matmul(jt, s(4:6))
        c = -matmul(l, m)
        call add_force_pair(loads, d%body_a, kin%r(:, d%body_a), d%body_b, kin%r(:, d%body_b), pup, f, c)
    end subroutine apply_disc

end module hn_discs
