!> Three-dimensional orientation of a body from its rotation matrix S
!! (body axes -> R, as hn_rotation): the Bryant angles of the model's own
!! sequence (Cardan x-y-z, body-fixed: S = Rx(alpha) Ry(beta) Rz(gamma),
!! the sequence of every joint's RX, RY, RZ coordinates) and the total
!! rotation angle (the magnitude of the rotation vector, 0 to pi); the
!! planar angles (the rotation projected on the three planes of the axes);
!! and the signed extreme of a sampled curve (the value of largest
!! magnitude).
module hn_head_angles
    use hn_kinds, only: wp, one, pi
    use hn_rotation, only: rotation_vector, norm3
    implicit none
    private

    public :: bryant_angles, bryant_angles_near, rotation_angle, planar_angles, signed_extreme, extreme_index

contains

    !> Bryant angles (alpha, beta, gamma) [rad] with S = Rx(alpha) Ry(beta)
    !! Rz(gamma): alpha and gamma in (-pi, pi], beta in [-pi/2, pi/2]. At
    !! beta = +-pi/2 (the sequence's singularity) alpha + gamma is split
    !! with gamma = atan2(S21, S22) and alpha = 0.
    pure function bryant_angles(s) result(q)
        real(wp), intent(in) :: s(3, 3)   !! rotation matrix (orthonormal, det +1)
        real(wp) :: q(3)
        real(wp) :: c2
        q(2) = asin(max(-one, min(one, s(1, 3))))
        c2 = sqrt(s(1, 1)**2 + s(1, 2)**2)
        if (c2 > 1.0e-12_wp) then
            q(1) = atan2(-s(2, 3), s(3, 3))
            q(3) = atan2(-s(1, 2), s(1, 1))
        else
            q(1) = 0.0_wp
            q(3) = atan2(s(2, 1), s(2, 2))
        end if
    end function bryant_angles

    !> The Bryant angles of S that continue `near` (the angles of the sample
    !! before): of the two triples that give S, (alpha, beta, gamma) and
    !! (alpha + pi, pi - beta, gamma + pi), each angle moved by whole turns
    !! to lie within pi of `near`, the triple closer to `near`. A head that
    !! pitches past 90 deg keeps alpha and gamma near zero and beta going on
    !! (the principal triple would jump to alpha = gamma = 180 deg there).
    pure function bryant_angles_near(s, near) result(q)
        real(wp), intent(in) :: s(3, 3)    !! rotation matrix (orthonormal, det +1)
        real(wp), intent(in) :: near(3)    !! the angles to continue [rad]
        real(wp) :: q(3)
        real(wp) :: a(3), b(3)
        a = bryant_angles(s)
        b = [a(1) + pi, pi - a(2), a(3) + pi]
        a = a + 2*pi*anint((near - a)/(2*pi))
        b = b + 2*pi*anint((near - b)/(2*pi))
        if (sum((b - near)**2) < sum((a - near)**2)) then
            q = b
        else
            q = a
        end if
    end function bryant_angles_near

    !> Total rotation angle of S [rad], 0 to pi: the angle of the single
    !! rotation about one axis that turns R into the body's axes.
    pure real(wp) function rotation_angle(s) result(a)
        real(wp), intent(in) :: s(3, 3)   !! rotation matrix (orthonormal, det +1)
        a = norm3(rotation_vector(s))
    end function rotation_angle

    !> Planar angles of S [rad], each in (-pi, pi]: the rotation seen in one
    !! plane of the reference axes. About x (the y-z plane, lateral
    !! bending): the angle of the body's z axis, atan2(-S23, S33); about y
    !! (the x-z plane, flexion): the body's z axis, atan2(S13, S33); about
    !! z (the x-y plane, twist): the body's x axis, atan2(S21, S11). A
    !! rotation about one axis alone gives its angle there and zero in the
    !! other two; the angle about x equals the first Bryant angle.
    pure function planar_angles(s) result(q)
        real(wp), intent(in) :: s(3, 3)   !! rotation matrix (orthonormal, det +1)
        real(wp) :: q(3)
        q = [atan2(-s(2, 3), s(3, 3)), atan2(s(1, 3), s(3, 3)), atan2(s(2, 1), s(1, 1))]
    end function planar_angles

    !> The value of largest magnitude of x, its sign kept.
    pure real(wp) function signed_extreme(x) result(e)
        real(wp), intent(in) :: x(:)   !! sampled curve (at least one value)
        e = x(extreme_index(x))
    end function signed_extreme

    !> Index of the value of largest magnitude of x (the first when several
    !! are equal).
    pure integer function extreme_index(x) result(k)
        real(wp), intent(in) :: x(:)   !! sampled curve (at least one value)
        k = maxloc(abs(x), dim=1)
    end function extreme_index

end module hn_head_angles
