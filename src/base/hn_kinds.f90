!> Working precision and physical constants shared by every module.
module hn_kinds
    use iso_fortran_env, only: real64, int64
    implicit none
    private

    public :: wp, i8, pi, g_std, zero, one, two, half, deg, msglen

    integer, parameter :: wp = real64   !! the single real kind of the project
    integer, parameter :: i8 = int64    !! integer kind for clock counts
    integer, parameter :: msglen = 512  !! length of error-message buffers

    real(wp), parameter :: zero = 0.0_wp
    real(wp), parameter :: one = 1.0_wp
    real(wp), parameter :: two = 2.0_wp
    real(wp), parameter :: half = 0.5_wp
    real(wp), parameter :: pi = 3.14159265358979323846264338327950288_wp
    real(wp), parameter :: g_std = 9.80665_wp        !! standard gravity [m/s^2]
    real(wp), parameter :: deg = pi/180.0_wp         !! one degree in radians
end module hn_kinds
