! SPDX-License-Identifier: Apache-2.0
!> Version of the library, kept in step with fpm.toml, CMakeLists.txt and include/hcimpact.h.
!>
!> The module is not called hcimpact_version: that is the C function
!> `hcimpact_version()`, and gfortran miscompiles a binding label equal to a module
!> name (doc/c-api.md).
module hcimpact_version_info
   implicit none
   private

   public :: hcimpact_version_string, hcimpact_version_compact, get_hcimpact_version

   !> Major version number
   integer, parameter :: version_major = 0
   !> Minor version number
   integer, parameter :: version_minor = 2
   !> Patch version number
   integer, parameter :: version_patch = 0
   !> Version as a string, "major.minor.patch"
   character(len=*), parameter :: hcimpact_version_string = "0.2.0"
   !> Version as one integer, 10000*major + 100*minor + patch
   integer, parameter :: hcimpact_version_compact = &
      & 10000*version_major + 100*version_minor + version_patch

contains

   !> Split the version into its three numbers.
   pure subroutine get_hcimpact_version(major, minor, patch)
      !> Major version number
      integer, intent(out), optional :: major
      !> Minor version number
      integer, intent(out), optional :: minor
      !> Patch version number
      integer, intent(out), optional :: patch
      if (present(major)) major = version_major
      if (present(minor)) minor = version_minor
      if (present(patch)) patch = version_patch
   end subroutine get_hcimpact_version

end module hcimpact_version_info
