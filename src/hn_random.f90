!> A small, portable random-number stream for designs of experiments: the
!! Park–Miller "minimal standard" generator with multiplier 48271
!! (x <- 48271 x mod (2^31 - 1)), in 64-bit integers so that no product
!! overflows. The same seed gives the same design with every compiler and
!! on every MPI rank, which the intrinsic random_number does not promise.
module hn_random
    use hn_kinds, only: wp, i8
    implicit none
    private

    public :: rng_t, rng_seed, rng_uniform, rng_permutation

    integer(i8), parameter :: modulus = 2147483647_i8   !! 2^31 - 1
    integer(i8), parameter :: multiplier = 48271_i8

    !> State of one stream.
    type :: rng_t
        integer(i8) :: x = 1_i8
    end type rng_t

contains

    !> Start a stream from a seed in [1, 2^31 - 2] (other seeds are folded in).
    pure subroutine rng_seed(rng, seed)
        type(rng_t), intent(out) :: rng
        integer, intent(in) :: seed
        rng%x = modulo(int(seed, i8), modulus - 1_i8) + 1_i8
    end subroutine rng_seed

    !> Next number, uniform in the open interval (0, 1).
    pure subroutine rng_uniform(rng, u)
        type(rng_t), intent(inout) :: rng
        real(wp), intent(out) :: u
        rng%x = modulo(multiplier*rng%x, modulus)
        u = real(rng%x, wp)/real(modulus, wp)
    end subroutine rng_uniform

    !> A random permutation of 1..n (Fisher–Yates).
    pure subroutine rng_permutation(rng, p)
        type(rng_t), intent(inout) :: rng
        integer, intent(out) :: p(:)
        integer :: i, j, tmp
        real(wp) :: u
        p = [(i, i=1, size(p))]
        do i = size(p), 2, -1
            call rng_uniform(rng, u)
            j = 1 + min(i - 1, int(u*i))
            tmp = p(i); p(i) = p(j); p(j) = tmp
        end do
    end subroutine rng_permutation

end module hn_random
