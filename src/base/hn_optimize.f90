!> Derivative-free minimisation on the unit cube, generic: Nelder-Mead
!! (reflection 1, expansion 2, contractions 1/2, shrink 1/2; points clamped
!! to [0, 1]), Nelder-Mead restarted about its best point while a restart
!! gains, and Latin-hypercube starting points (one point in each of n
!! equal strata per coordinate, strata paired at random, seeded: the same
!! points on every machine). The objective is any function of a point of
!! the unit cube (`objective_fn`); a caller maps the cube onto its own
!! parameters (the calibration: hn_calibrate; the sweep designs: hn_sweep).
module hn_optimize
    use hn_kinds, only: wp, zero, one
    use hn_random, only: rng_t
    use hn_sorting, only: sort_index
    implicit none
    private

    public :: objective_fn, nelder_mead, restarted_nelder_mead, latin_hypercube

    abstract interface
        !> An objective on the unit cube.
        function objective_fn(u) result(f)
            import :: wp
            real(wp), intent(in) :: u(:)             !! point in the unit cube
            real(wp) :: f
        end function objective_fn
    end interface

contains

    !> Nelder-Mead on the unit cube from u0 with initial steps `step`;
    !! points clamped to [0, 1]; stops after max_evals evaluations or when
    !! the simplex's objective values agree within ftol.
    subroutine nelder_mead(f, u0, step, max_evals, ftol, ubest, fbest, nevals)
        procedure(objective_fn) :: f             !! the objective
        real(wp), intent(in) :: u0(:)            !! starting point in the unit cube
        real(wp), intent(in) :: step             !! initial simplex step
        integer, intent(in) :: max_evals         !! most evaluations
        real(wp), intent(in) :: ftol             !! stop when the simplex's values agree within ftol
        real(wp), intent(out) :: ubest(size(u0)) !! best point
        real(wp), intent(out) :: fbest           !! objective there
        integer, intent(out) :: nevals           !! evaluations made
        real(wp) :: x(size(u0), size(u0) + 1), fx(size(u0) + 1), xc(size(u0)), xr(size(u0)), xe(size(u0))
        real(wp) :: xk(size(u0)), fr, fe, fk
        integer :: n, i, order(size(u0) + 1)
        n = size(u0)
        x(:, 1) = u0
        do i = 1, n
            x(:, i + 1) = u0
            x(i, i + 1) = u0(i) + merge(step, -step, u0(i) + step <= one)
        end do
        nevals = 0
        do i = 1, n + 1
            fx(i) = feval(x(:, i))
        end do
        do while (nevals < max_evals)
            order = sort_index(fx)
            x = x(:, order); fx = fx(order)
            if (fx(n + 1) - fx(1) <= ftol) exit
            xc = sum(x(:, 1:n), dim=2)/n
            xr = clamp(xc + (xc - x(:, n + 1)))
            fr = feval(xr)
            if (fr < fx(1)) then
                xe = clamp(xc + 2*(xc - x(:, n + 1)))
                fe = feval(xe)
                if (fe < fr) then
                    x(:, n + 1) = xe; fx(n + 1) = fe
                else
                    x(:, n + 1) = xr; fx(n + 1) = fr
                end if
            else if (fr < fx(n)) then
                x(:, n + 1) = xr; fx(n + 1) = fr
            else
                if (fr < fx(n + 1)) then
                    xk = clamp(xc + 0.5_wp*(xr - xc))          ! outside contraction
                else
                    xk = clamp(xc + 0.5_wp*(x(:, n + 1) - xc)) ! inside contraction
                end if
                fk = feval(xk)
                if (fk < min(fr, fx(n + 1))) then
                    x(:, n + 1) = xk; fx(n + 1) = fk
                else
                    do i = 2, n + 1                            ! shrink towards the best
                        x(:, i) = x(:, 1) + 0.5_wp*(x(:, i) - x(:, 1))
                        fx(i) = feval(x(:, i))
                    end do
                end if
            end if
        end do
        i = minloc(fx, dim=1)
        ubest = x(:, i); fbest = fx(i)
    contains
        real(wp) function feval(u)
            real(wp), intent(in) :: u(:)
            feval = f(u)
            nevals = nevals + 1
        end function feval
    end subroutine nelder_mead

    !> Nelder-Mead from u0, then restarted with a fresh simplex (the same
    !! step) about its best point while a restart lowers the objective by
    !! more than ftol and evaluations for one more simplex are left: a
    !! simplex that has collapsed short of the minimum starts again.
    subroutine restarted_nelder_mead(f, u0, step, max_evals, ftol, ubest, fbest, nevals)
        procedure(objective_fn) :: f             !! the objective
        real(wp), intent(in) :: u0(:)            !! starting point in the unit cube
        real(wp), intent(in) :: step             !! initial simplex step of every run
        integer, intent(in) :: max_evals         !! most evaluations in all
        real(wp), intent(in) :: ftol             !! a run stops when its simplex's values agree within ftol
        real(wp), intent(out) :: ubest(size(u0)) !! best point
        real(wp), intent(out) :: fbest           !! objective there
        integer, intent(out) :: nevals           !! evaluations made
        real(wp) :: unew(size(u0)), fnew
        integer :: n
        logical :: gained
        call nelder_mead(f, u0, step, max_evals, ftol, ubest, fbest, nevals)
        do while (max_evals - nevals > 2*(size(u0) + 1))
            call nelder_mead(f, ubest, step, max_evals - nevals, ftol, unew, fnew, n)
            nevals = nevals + n
            gained = fbest - fnew > ftol
            if (fnew < fbest) then
                ubest = unew; fbest = fnew
            end if
            if (.not. gained) exit
        end do
    end subroutine restarted_nelder_mead

    !> A Latin hypercube of npoints points in the unit cube of dimension
    !! ndim: coordinate p of point r lies in stratum perm_p(r) of npoints
    !! equal strata, at a uniform deviate within it; one random permutation
    !! per coordinate, coordinates in turn, from a SplitMix64 stream seeded
    !! with `seed` (hn_random), so the same seed gives the same points on
    !! every machine and rank.
    function latin_hypercube(ndim, npoints, seed) result(u)
        integer, intent(in) :: ndim              !! dimension of the cube
        integer, intent(in) :: npoints           !! number of points (and of strata per coordinate)
        integer, intent(in) :: seed              !! seed of the random stream
        real(wp) :: u(ndim, npoints)
        integer :: perm(npoints), p, r
        type(rng_t) :: rng
        call rng%seed(seed)
        do p = 1, ndim
            call rng%permutation(perm)
            do r = 1, npoints
                u(p, r) = (real(perm(r) - 1, wp) + rng%uniform(zero, one))/real(npoints, wp)
            end do
        end do
    end function latin_hypercube

    pure function clamp(u) result(c)
        real(wp), intent(in) :: u(:)
        real(wp) :: c(size(u))
        c = min(one, max(zero, u))
    end function clamp

end module hn_optimize
