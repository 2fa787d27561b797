!> Rotation matrices, Bryant angles and small vector algebra.
!!
!! Convention: a rotation matrix `S` maps components in a rotated (body) frame
!! to components in the reference frame, `v_ref = matmul(S, v_body)`.
!! Relative orientation of a child body uses Bryant (Cardan x-y-z, body-fixed)
!! angles (alpha, beta, gamma): `R = Rx(alpha) Ry(beta) Rz(gamma)`. The sequence
!! is singular where cos(beta) = 0, i.e. beta = +-90 degrees, where the first and
!! third rotation axes coincide.
module hn_rotation
    use hn_kinds, only: wp, zero, one, half
    implicit none
    private

    public :: cross, skew, rot_y, bryant_matrix, bryant_axes
    public :: rotation_vector, axis_angle_matrix, norm3, unit_matrix

contains

    !> Cross product a x b.
    pure function cross(a, b) result(c)
        real(wp), intent(in) :: a(3)   !! first factor
        real(wp), intent(in) :: b(3)   !! second factor
        real(wp) :: c(3)
        c(1) = a(2)*b(3) - a(3)*b(2)
        c(2) = a(3)*b(1) - a(1)*b(3)
        c(3) = a(1)*b(2) - a(2)*b(1)
    end function cross

    !> Skew-symmetric matrix with skew(a) b = a x b.
    pure function skew(a) result(m)
        real(wp), intent(in) :: a(3)   !! the vector whose cross product the matrix applies
        real(wp) :: m(3, 3)
        m(:, 1) = [zero, a(3), -a(2)]
        m(:, 2) = [-a(3), zero, a(1)]
        m(:, 3) = [a(2), -a(1), zero]
    end function skew

    !> Euclidean norm of a 3-vector.
    pure real(wp) function norm3(a)
        real(wp), intent(in) :: a(3)   !! the vector
        norm3 = sqrt(a(1)**2 + a(2)**2 + a(3)**2)
    end function norm3

    !> 3x3 identity.
    pure function unit_matrix() result(m)
        real(wp) :: m(3, 3)
        m = zero
        m(1, 1) = one; m(2, 2) = one; m(3, 3) = one
    end function unit_matrix


    !> Rotation by angle a [rad] about y.
    pure function rot_y(a) result(m)
        real(wp), intent(in) :: a   !! angle [rad], right-handed about y
        real(wp) :: m(3, 3)
        real(wp) :: c, s
        c = cos(a); s = sin(a)
        m = reshape([c, zero, -s, zero, one, zero, s, zero, c], [3, 3])
    end function rot_y


    !> Bryant-angle matrix Rx(q1) Ry(q2) Rz(q3) (child components -> parent components).
    pure function bryant_matrix(q) result(m)
        real(wp), intent(in) :: q(3)   !! Bryant angles (alpha, beta, gamma) about x, y', z'' [rad]
        real(wp) :: m(3, 3)
        real(wp) :: c1, s1, c2, s2, c3, s3
        c1 = cos(q(1)); s1 = sin(q(1))
        c2 = cos(q(2)); s2 = sin(q(2))
        c3 = cos(q(3)); s3 = sin(q(3))
        m(1, 1) = c2*c3
        m(2, 1) = s1*s2*c3 + c1*s3
        m(3, 1) = -c1*s2*c3 + s1*s3
        m(1, 2) = -c2*s3
        m(2, 2) = -s1*s2*s3 + c1*c3
        m(3, 2) = c1*s2*s3 + s1*c3
        m(1, 3) = s2
        m(2, 3) = -s1*c2
        m(3, 3) = c1*c2
    end function bryant_matrix

    !> The three Bryant rotation axes in parent components: e1, Rx(q1) e2,
    !! Rx(q1) Ry(q2) e3. The relative angular velocity is sum(axes(:,m) * qdot(m)).
    pure function bryant_axes(q) result(u)
        real(wp), intent(in) :: q(3)   !! Bryant angles (alpha, beta, gamma) [rad]; gamma is not used
        real(wp) :: u(3, 3)
        real(wp) :: c1, s1, c2, s2
        c1 = cos(q(1)); s1 = sin(q(1))
        c2 = cos(q(2)); s2 = sin(q(2))
        u(:, 1) = [one, zero, zero]
        u(:, 2) = [zero, c1, s1]
        u(:, 3) = [s2, -s1*c2, c1*c2]
    end function bryant_axes


    !> Rotation vector theta*n (axis n, angle theta in [0, pi]) of a rotation matrix.
    pure function rotation_vector(m) result(v)
        real(wp), intent(in) :: m(3, 3)   !! rotation matrix (orthonormal, det +1)
        real(wp) :: v(3)
        real(wp) :: c, s, th, w(3), b(3, 3)
        integer :: k
        w = half*[m(3, 2) - m(2, 3), m(1, 3) - m(3, 1), m(2, 1) - m(1, 2)]
        s = norm3(w)
        c = half*(m(1, 1) + m(2, 2) + m(3, 3) - one)
        th = atan2(s, c)
        if (s > 1.0e-6_wp .or. c > zero) then
            if (s < 1.0e-12_wp) then
                v = w
            else
                v = w*(th/s)
            end if
            ! near theta = 0: th/s -> 1 + s^2/6 ; the formula above is accurate there
        else
            ! theta close to pi: axis from the symmetric part
            b = half*(m + transpose(m))
            k = maxloc([b(1, 1), b(2, 2), b(3, 3)], dim=1)
            v = b(:, k)
            v(k) = b(k, k) - c
            v = v/norm3(v)
            if (dot_product(v, w) < zero) v = -v
            v = v*th
        end if
    end function rotation_vector

    !> Rotation matrix of the rotation vector v (Rodrigues).
    pure function axis_angle_matrix(v) result(m)
        real(wp), intent(in) :: v(3)   !! rotation vector: axis times angle [rad]
        real(wp) :: m(3, 3)
        real(wp) :: th, a, b, k(3, 3)
        th = norm3(v)
        k = skew(v)
        if (th < 1.0e-8_wp) then
            a = one - th**2/6.0_wp
            b = half - th**2/24.0_wp
        else
            a = sin(th)/th
            b = (one - cos(th))/th**2
        end if
        m = unit_matrix() + a*k + b*matmul(k, k)
    end function axis_angle_matrix

end module hn_rotation
