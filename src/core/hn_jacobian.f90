!> Generalized stiffness K and damping C of the model's elements: the
!! tangent of the element loads, mapped through the joint columns (the
!! partial velocities) onto the active coordinates. With a_ij they give the
!! structured Jacobian of the equations of motion used by the stiff
!! integrators: d(xddot)/dx ~ -a^-1 K, d(xddot)/dxdot ~ -a^-1 C.
!!
!! Each element has a deformation rate that is linear in xdot,
!! delta' = B xdot (B exact: the element's geometry), and loads whose
!! generalized forces are Q = -B^T s(delta, delta'). Then
!!   K = B^T (ds/d delta) B,   C = B^T (ds/d delta') B,
!! leaving out the terms of dB/dx s (geometric stiffness) and the
!! dependence of a_ij, gravity and the velocity terms on x: an approximate
!! Jacobian, which the Rosenbrock-W method tolerates by construction. The
!! tangent of each element's law ds/d delta, ds/d delta' is a central
!! difference of the law itself, so any present or future law gets one.
!!   discs         delta = q (6 deformations), s = disc_resultants(q, qd)
!!   line elements delta = length L, s = tension T(L, L')
!!   joint dampers the generalized force on their coordinate directly
!! B of an element is nonzero only on the coordinates between its two
!! bodies: for a common ancestor's coordinate the two ends move as one
!! rigid body and the contributions cancel exactly.
module hn_jacobian
    use hn_kinds, only: wp, zero, one
    use hn_rotation, only: cross
    use hn_model, only: model_t, fam_discs, fam_ligaments, fam_muscles, fam_limits, fam_springs, family_count
    use hn_kinematics, only: kinematics_t
    use hn_tree, only: body_tree_t
    use hn_discs, only: disc_deformation, disc_resultants, inv_left_jacobian
    use hn_line_elements, only: line_attach_t, line_geometry_t, line_geometry, ligament_tension, muscle_tension, &
                                spring_tension, max_via, muscle_path_points
    use hn_joint_limits, only: limit_force, range_moment
    use hn_forces, only: muscle_activation
    implicit none
    private

    public :: generalized_tangent

    !> Relative step of the central differences of the element laws, and the
    !! smallest absolute steps [m, m/s, rad, rad/s] (laws are smooth on that
    !! scale; a kink inside the interval gives the mean slope).
    real(wp), parameter :: fd_rel = 1.0e-6_wp
    real(wp), parameter :: fd_abs_length = 1.0e-9_wp, fd_abs_rate = 1.0e-6_wp

contains

    !> K and C (n x n, all active coordinates) of every element switched on,
    !! for the kinematics kin of the state (x, xd) at time t (kin from
    !! body_kinematics or partial_velocities: joint columns filled).
    pure subroutine generalized_tangent(model, kin, t, x, xd, kgen, cgen)
        type(model_t), intent(in) :: model      !! the model (elements and the families switched on)
        type(kinematics_t), intent(in) :: kin   !! kinematics of (x, xd): joint columns filled
        real(wp), intent(in) :: t               !! time [s] (for the muscles' activation)
        real(wp), intent(in) :: x(:)            !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)           !! their rates [m/s, rad/s]
        real(wp), intent(out) :: kgen(:, :)     !! (n,n) generalized stiffness [N/m, N m/rad, ...]
        real(wp), intent(out) :: cgen(:, :)     !! (n,n) generalized damping
        integer :: e, fam
        integer, parameter :: line_families(3) = [fam_ligaments, fam_muscles, fam_springs]
        ! scratch of the element terms, sized once here rather than in every element's call
        integer :: cols(max(size(kgen, 1), 1)), sgn(size(cols)), idx(size(cols))
        real(wp) :: b(size(cols)), bd(6, size(cols))
        kgen = zero
        cgen = zero
        if (model%family_on(fam_discs)) then
            do e = 1, size(model%discs)
                call add_disc(model, kin, e, kgen, cgen, cols, sgn, bd)
            end do
        end if
        do fam = 1, size(line_families)
            if (.not. model%family_on(line_families(fam))) cycle
            do e = 1, family_count(model, line_families(fam))
                call add_line(model, kin, t, line_families(fam), e, kgen, cgen, cols, sgn, idx, b)
            end do
        end do
        if (model%family_on(fam_limits)) then
            do e = 1, size(model%limits)
                call add_limit(model, e, x, xd, kgen, cgen)
            end do
            do e = 1, size(model%ranges)
                call add_range(model, e, x, kgen)
            end do
        end if
    end subroutine generalized_tangent

    ! ---------------------------------------------------------------------
    ! Coupling to the line-element types: the only place that knows the
    ! families (ligament_t, muscle_t, spring_t, each a line_attach_t).
    ! ---------------------------------------------------------------------

    !> Path of line element e of a family: its points in order (bodies and
    !! body-frame positions): the two ends, and a muscle's via points between.
    pure subroutine line_path(model, fam, e, bodies, points, npt)
        type(model_t), intent(in) :: model
        integer, intent(in) :: fam, e
        integer, intent(out) :: bodies(max_via + 2), npt
        real(wp), intent(out) :: points(3, max_via + 2)
        type(line_attach_t) :: a
        if (fam == fam_muscles) then
            call muscle_path_points(model%muscles(e), bodies, points, npt)
            return
        end if
        select case (fam)
        case (fam_ligaments); a = model%ligaments(e)%line_attach_t
        case default; a = model%springs(e)%line_attach_t
        end select
        bodies = 0; points = zero; npt = 2
        bodies(1) = a%body_a; bodies(2) = a%body_b
        points(:, 1) = a%point_a; points(:, 2) = a%point_b
    end subroutine line_path

    !> The scalar tension law of line element e at time t, length L and rate L'.
    pure real(wp) function line_tension(model, fam, e, t, length, rate) result(ten)
        type(model_t), intent(in) :: model
        integer, intent(in) :: fam, e
        real(wp), intent(in) :: t, length, rate
        real(wp) :: act
        select case (fam)
        case (fam_ligaments)
            ten = ligament_tension(model%ligaments(e), length)
        case (fam_muscles)
            act = muscle_activation(model, e, t)
            ten = muscle_tension(model%muscles(e), length, rate, act)
        case default
            ten = spring_tension(model%springs(e), length, rate)
        end select
    end function line_tension

    ! --------------------------------------------------------------------- end of the coupling

    !> Line element: b_i = dL/dxdot_i = sj_i . phi_b - sj_i . phi_a with the
    !! spatial force phi = ((p - origin) x u; u) of a unit tension at each
    !! end, summed over the segments of a muscle's path through its via
    !! points; K += (dT/dL) b b^T, C += (dT/dL') b b^T.
    pure subroutine add_line(model, kin, t, fam, e, kgen, cgen, cols, sgn, idx, b)
        type(model_t), intent(in) :: model
        type(kinematics_t), intent(in) :: kin
        real(wp), intent(in) :: t
        integer, intent(in) :: fam, e
        real(wp), intent(inout) :: kgen(:, :), cgen(:, :)
        integer, intent(out) :: cols(:), sgn(:), idx(:)   ! scratch, at least n long
        real(wp), intent(out) :: b(:)                      ! scratch, n long
        type(line_geometry_t) :: g
        integer :: bodies(max_via + 2), npt, k, ncol, i, nz
        real(wp) :: points(3, max_via + 2), phia(6), phib(6), length, rate, dl, dr, kl, cl
        call line_path(model, fam, e, bodies, points, npt)
        b = zero; length = zero; rate = zero
        do k = 1, npt - 1
            call line_geometry(kin, bodies(k), points(:, k), bodies(k + 1), points(:, k + 1), g)
            if (g%length <= zero) return
            length = length + g%length
            rate = rate + g%rate
            phia = [cross(g%pa - kin%origin, g%unit), g%unit]
            phib = [cross(g%pb - kin%origin, g%unit), g%unit]
            call path_columns(model%tree, bodies(k), bodies(k + 1), cols, sgn, ncol)
            do i = 1, ncol
                if (sgn(i) > 0) then
                    b(cols(i)) = b(cols(i)) + dot_product(kin%sj(:, cols(i)), phib)
                else
                    b(cols(i)) = b(cols(i)) - dot_product(kin%sj(:, cols(i)), phia)
                end if
            end do
        end do
        dl = max(fd_rel*length, fd_abs_length)
        dr = max(fd_rel*abs(rate), fd_abs_rate)
        kl = (line_tension(model, fam, e, t, length + dl, rate) - &
              line_tension(model, fam, e, t, length - dl, rate))/(2*dl)
        cl = (line_tension(model, fam, e, t, length, rate + dr) - &
              line_tension(model, fam, e, t, length, rate - dr))/(2*dr)
        if (kl == zero .and. cl == zero) return
        nz = 0
        do i = 1, size(kgen, 1)
            if (b(i) /= zero) then
                nz = nz + 1
                idx(nz) = i
            end if
        end do
        do i = 1, nz
            kgen(idx(1:nz), idx(i)) = kgen(idx(1:nz), idx(i)) + kl*b(idx(i))*b(idx(1:nz))
            cgen(idx(1:nz), idx(i)) = cgen(idx(1:nz), idx(i)) + cl*b(idx(i))*b(idx(1:nz))
        end do
    end subroutine add_line

    !> Disc: qd = B xdot with column B_i = +-G sj_i, G mapping a motion
    !! vector (w; v) to (L^T (v + w x (P_u - origin)); J^-1 L^T w) (P_u the
    !! upper plate centre where the loads act; + for the upper body's
    !! coordinates, - for the lower's); ds/dq and ds/dqd by central
    !! differences of disc_resultants.
    pure subroutine add_disc(model, kin, e, kgen, cgen, cols, sgn, b)
        type(model_t), intent(in) :: model
        type(kinematics_t), intent(in) :: kin
        integer, intent(in) :: e
        real(wp), intent(inout) :: kgen(:, :), cgen(:, :)
        integer, intent(out) :: cols(:), sgn(:)   ! scratch, at least n long
        real(wp), intent(out) :: b(:, :)           ! scratch, (6, n)
        integer :: ncol, i, m
        real(wp) :: q(6), qd(6), l(3, 3), pup(3), ks(6, 6), cs(6, 6), dq(6), step, jinv(3, 3), pr(3)
        real(wp) :: w(3), v(3)
        associate (d => model%discs(e))
            call disc_deformation(d, kin, q, qd, l, pup)
            do m = 1, 6
                dq = zero
                step = max(fd_rel*abs(q(m)), fd_abs_length)
                dq(m) = step
                ks(:, m) = (disc_resultants(d, q + dq, qd) - disc_resultants(d, q - dq, qd))/(2*step)
                step = max(fd_rel*abs(qd(m)), fd_abs_rate)
                dq(m) = step
                cs(:, m) = (disc_resultants(d, q, qd + dq) - disc_resultants(d, q, qd - dq))/(2*step)
            end do
            jinv = inv_left_jacobian(q(4:6))
            pr = pup - kin%origin
            call path_columns(model%tree, d%body_a, d%body_b, cols, sgn, ncol)
        end associate
        do i = 1, ncol
            w = kin%sj(1:3, cols(i))
            v = kin%sj(4:6, cols(i)) + cross(w, pr)
            b(1:3, i) = sgn(i)*matmul(v, l)
            b(4:6, i) = sgn(i)*matmul(jinv, matmul(w, l))
        end do
        kgen(cols(1:ncol), cols(1:ncol)) = kgen(cols(1:ncol), cols(1:ncol)) + &
                                           matmul(transpose(b(:, 1:ncol)), matmul(ks, b(:, 1:ncol)))
        cgen(cols(1:ncol), cols(1:ncol)) = cgen(cols(1:ncol), cols(1:ncol)) + &
                                           matmul(transpose(b(:, 1:ncol)), matmul(cs, b(:, 1:ncol)))
    end subroutine add_disc

    !> Joint damper on one coordinate: -dQ/dx and -dQ/dxdot of its law.
    pure subroutine add_limit(model, e, x, xd, kgen, cgen)
        type(model_t), intent(in) :: model
        integer, intent(in) :: e
        real(wp), intent(in) :: x(:), xd(:)
        real(wp), intent(inout) :: kgen(:, :), cgen(:, :)
        real(wp) :: dx, dv
        integer :: j
        associate (lim => model%limits(e))
            j = lim%dof
            dx = max(fd_rel*abs(x(j)), fd_abs_length)
            dv = max(fd_rel*abs(xd(j)), fd_abs_rate)
            kgen(j, j) = kgen(j, j) - (limit_force(lim, x(j) + dx, xd(j)) - limit_force(lim, x(j) - dx, xd(j)))/(2*dx)
            cgen(j, j) = cgen(j, j) - (limit_force(lim, x(j), xd(j) + dv) - limit_force(lim, x(j), xd(j) - dv))/(2*dv)
        end associate
    end subroutine add_limit

    !> Range-of-motion stop (elastic beyond the range): K_jj -= dQ/dx.
    pure subroutine add_range(model, e, x, kgen)
        type(model_t), intent(in) :: model
        integer, intent(in) :: e
        real(wp), intent(in) :: x(:)
        real(wp), intent(inout) :: kgen(:, :)
        real(wp) :: dx
        integer :: j
        associate (r => model%ranges(e))
            j = r%dof
            dx = max(fd_rel*abs(x(j)), fd_abs_length)
            kgen(j, j) = kgen(j, j) - (range_moment(r, x(j) + dx) - range_moment(r, x(j) - dx))/(2*dx)
        end associate
    end subroutine add_range

    !> Coordinates on the tree path between bodies ka and kb (0 = R): those
    !! in exactly one of the two chains, ascending, with sign +1 for kb's,
    !! -1 for ka's. The chains are ascending: one merge of the two lists.
    pure subroutine path_columns(tree, ka, kb, cols, sgn, ncol)
        type(body_tree_t), intent(in) :: tree
        integer, intent(in) :: ka, kb
        integer, intent(out) :: cols(:), sgn(:), ncol
        integer :: ia, ib, na, nb, ja, jb
        na = 0; nb = 0
        if (ka > 0) na = tree%chain_len(ka)
        if (kb > 0) nb = tree%chain_len(kb)
        ia = 1; ib = 1; ncol = 0
        do while (ia <= na .or. ib <= nb)
            ja = huge(ja); jb = huge(jb)
            if (ia <= na) ja = tree%chain(ia, ka)
            if (ib <= nb) jb = tree%chain(ib, kb)
            if (ja == jb) then          ! on both chains: the two ends move as one
                ia = ia + 1; ib = ib + 1
            else if (jb < ja) then
                ncol = ncol + 1; cols(ncol) = jb; sgn(ncol) = 1
                ib = ib + 1
            else
                ncol = ncol + 1; cols(ncol) = ja; sgn(ncol) = -1
                ia = ia + 1
            end if
        end do
    end subroutine path_columns

end module hn_jacobian
