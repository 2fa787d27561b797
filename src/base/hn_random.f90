!> A small, portable random-number stream: SplitMix64 (Steele, Lea &
!! Flood, OOPSLA 2014), which gives the same numbers with every compiler, on
!! every machine and on every MPI rank (the intrinsic random_number
!! promises none of that). Used by the designs of experiments of sweeps and
!! by the random states of the tests. The state update relies on 64-bit
!! two's-complement wrap-around, as every Fortran compiler in use does
!! (do not build with integer-overflow trapping).
module hn_random
    use hn_kinds, only: wp, i8
    implicit none
    private

    public :: rng_t

    !> State of one stream; a default-initialised stream is reproducible.
    type :: rng_t
        integer(i8) :: s = 88172645463325252_i8
    contains
        procedure :: seed => rng_seed
        procedure :: uniform => rng_uniform
        procedure :: permutation => rng_permutation
    end type rng_t

contains

    !> Restart the stream from an integer seed.
    pure subroutine rng_seed(me, seed)
        class(rng_t), intent(inout) :: me
        integer, intent(in) :: seed   !! any integer; equal seeds give equal streams
        me%s = 88172645463325252_i8 + int(seed, i8)
    end subroutine rng_seed

    !> Uniform deviate in [a, b).
    real(wp) function rng_uniform(me, a, b) result(u)
        class(rng_t), intent(inout) :: me
        real(wp), intent(in) :: a   !! lower bound (included)
        real(wp), intent(in) :: b   !! upper bound (excluded)
        integer(i8) :: z
        me%s = me%s + (-7046029254386353131_i8)
        z = me%s
        z = ieor(z, shiftr(z, 30))*(-4658895280553007687_i8)
        z = ieor(z, shiftr(z, 27))*(-7723592293110705685_i8)
        z = ieor(z, shiftr(z, 31))
        u = a + (b - a)*real(shiftr(z, 11), wp)*2.0_wp**(-53)
    end function rng_uniform

    !> A random permutation of 1..size(p) (Fisher–Yates).
    subroutine rng_permutation(me, p)
        class(rng_t), intent(inout) :: me
        integer, intent(out) :: p(:)   !! a permutation of 1..size(p)
        integer :: i, j, tmp
        p = [(i, i=1, size(p))]
        do i = size(p), 2, -1
            j = 1 + min(i - 1, int(me%uniform(0.0_wp, 1.0_wp)*i))
            tmp = p(i); p(i) = p(j); p(j) = tmp
        end do
    end subroutine rng_permutation

end module hn_random
