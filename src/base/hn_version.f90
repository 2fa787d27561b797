!> The one version string of the code; fpm.toml's `version` must match it
!! (test_version checks).
module hn_version
    implicit none
    private

    public :: code_version

    character(len=*), parameter :: code_version = '0.3.0'   !! written in listings and result files
end module hn_version
