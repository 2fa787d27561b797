!> The two solvers of a_ij xddot_j = f_i: Gaussian elimination with partial
!! pivoting (own) and LAPACK Cholesky agree on the 54-DOF a_ij, recover a
!! manufactured solution within the condition bound, and refuse a singular matrix.
program test_solvers
    use hn_kinds, only: wp, zero, one, msglen
    use hn_tree, only: body_tree_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities
    use hn_kane, only: a_ij
    use hn_linsolve, only: gauss_solve, cholesky_solve, spd_rcond, linear_solve, solver_gauss, solver_cholesky
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t, random_tree
    implicit none

    type(test_suite_t) :: suite
    type(rng_t) :: rng
    type(body_tree_t) :: tree
    type(kinematics_t) :: kin
    real(wp), allocatable :: a(:, :), xtrue(:), b(:), x(:), xd(:)
    real(wp) :: rcond
    integer :: n, j

    call random_tree(tree, 9, rng)
    n = tree%ndof
    allocate (a(n, n), xtrue(n), b(n), x(n), xd(n))
    do j = 1, n
        x(j) = rng%uniform(-1.0_wp, 1.0_wp)
        xd(j) = rng%uniform(-1.0_wp, 1.0_wp)
        xtrue(j) = rng%uniform(-1.0_wp, 1.0_wp)
    end do
    call kinematics_allocate(tree, kin)
    call partial_velocities(tree, x, xd, kin)
    call a_ij(tree, kin, a)
    call spd_rcond(a, rcond)
    b = matmul(a, xtrue)

    call test_gauss_recovers_solution()
    call test_cholesky_recovers_solution()
    call test_solvers_agree()
    call test_singular_refused()
    call test_ill_conditioned_flagged()
    call suite%finish()

contains

    real(wp) function bound() result(bd)
        ! forward error bound: a few n eps / rcond
        bd = 10*n*epsilon(one)/rcond
    end function bound

    subroutine test_gauss_recovers_solution()
        real(wp) :: aw(n, n), bw(n)
        integer :: stat
        character(len=100) :: d
        aw = a; bw = b
        call gauss_solve(aw, bw, stat)
        write (d, '(a,es10.3,a,es10.3,a,es10.3)') 'rcond(a_ij) ', rcond, ', error ', &
            maxval(abs(bw - xtrue)), ', bound ', bound()
        call suite%check(stat == 0 .and. maxval(abs(bw - xtrue)) <= bound(), &
                         'Gaussian elimination recovers a manufactured solution at 54 DOF', d)
    end subroutine test_gauss_recovers_solution

    subroutine test_cholesky_recovers_solution()
        real(wp) :: aw(n, n), bw(n)
        integer :: stat
        character(len=100) :: d
        aw = a; bw = b
        call cholesky_solve(aw, bw, stat)
        write (d, '(a,es10.3,a,es10.3)') 'error ', maxval(abs(bw - xtrue)), ', bound ', bound()
        call suite%check(stat == 0 .and. maxval(abs(bw - xtrue)) <= bound(), &
                         'LAPACK Cholesky (dposv) recovers a manufactured solution at 54 DOF', d)
    end subroutine test_cholesky_recovers_solution

    subroutine test_solvers_agree()
        real(wp) :: a1(n, n), b1(n), a2(n, n), b2(n)
        integer :: s1, s2
        a1 = a; b1 = b; a2 = a; b2 = b
        call gauss_solve(a1, b1, s1)
        call cholesky_solve(a2, b2, s2)
        call suite%near(maxval(abs(b1 - b2))/maxval(abs(b2)), zero, bound(), &
                        'Gauss and Cholesky solutions of a_ij x = f agree')
    end subroutine test_solvers_agree

    subroutine test_singular_refused()
        real(wp) :: as(4, 4), bs(4), ac(4, 4), bc(4), v(4), w(4)
        integer :: s1, s2, i
        ! symmetric positive semi-definite of rank 2
        v = [1, 2, 3, 4]; w = [1, 0, 1, 0]
        do i = 1, 4
            as(:, i) = v*v(i) + w*w(i)
        end do
        bs = one
        ac = as; bc = bs
        call gauss_solve(as, bs, s1)
        call cholesky_solve(ac, bc, s2)
        call suite%check(s1 /= 0 .and. s2 /= 0, 'a singular symmetric matrix (rank 2 of 4) is refused by both solvers')
    end subroutine test_singular_refused

    !> diag(1, 1e-15): solvable, but flagged ill-conditioned by both solvers.
    subroutine test_ill_conditioned_flagged()
        real(wp) :: m(2, 2), r(2)
        integer :: s1, s2, row1, row2
        character(len=msglen) :: e1, e2
        m = reshape([one, zero, zero, 1.0e-15_wp], [2, 2]); r = one
        call linear_solve(solver_gauss, m, r, s1, e1, row1)
        m = reshape([one, zero, zero, 1.0e-15_wp], [2, 2]); r = one
        call linear_solve(solver_cholesky, m, r, s2, e2, row2)
        call suite%check(s1 /= 0 .and. s2 /= 0 .and. row1 == 2 .and. row2 == 2 .and. &
                         index(e1, 'ill-conditioned') > 0 .and. index(e2, 'ill-conditioned') > 0, &
                         'an ill-conditioned a_ij is flagged, with the row concerned', trim(e1))
    end subroutine test_ill_conditioned_flagged

end program test_solvers
