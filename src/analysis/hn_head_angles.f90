!> Three-dimensional orientation of a body from its rotation matrix S
!! (body axes -> R, as hn_rotation): the Bryant angles of the model's own
!! sequence (Cardan x-y-z, body-fixed: S = Rx(alpha) Ry(beta) Rz(gamma),
!! the sequence of every joint's RX, RY, RZ coordinates) and the total
!! rotation angle (the magnitude of the rotation vector, 0 to pi); and the
!! signed extreme of a sampled curve (the value of largest magnitude).
module hn_head_angles
    use hn_kinds, only: wp, one
    use hn_rotation, only: rotation_vector, norm3
    implicit none
    private

    public :: bryant_angles, rotation_angle, signed_extreme, extreme_index

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

    !> Total rotation angle of S [rad], 0 to pi: the angle of the single
    !! rotation about one axis that turns R into the body's axes.
    pure real(wp) function rotation_angle(s) result(a)
        real(wp), intent(in) :: s(3, 3)   !! rotation matrix (orthonormal, det +1)
        a = norm3(rotation_vector(s))
    end function rotation_angle

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
