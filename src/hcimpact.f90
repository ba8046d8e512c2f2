! SPDX-License-Identifier: Apache-2.0
!> Public Fortran API of hcimpact: the Hunt-Crossley model of a collinear impact.
!>
!> `use hcimpact` brings in everything a caller needs; the modules behind it may
!> also be used one by one.
module hcimpact
   use hcimpact_kinds, only : wp
   use hcimpact_version, only : hcimpact_version_string, hcimpact_version_compact, &
      & get_hcimpact_version
   use hcimpact_lambertw, only : lambert_w0, lambert_wm1, lambert_w0p1, lambert_wm1p1
   implicit none
   public

end module hcimpact
