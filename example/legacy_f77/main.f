C     SPDX-License-Identifier: Apache-2.0
C
C     The seed's steel ball through the FORTRAN 77 entry points of
C     hcimpact: a steel ball of mass 0.1 kg strikes a massive steel
C     plate (Hertz law F = C X**1.5, C = 1.7135E10 N/m**1.5, damping
C     B = 0.1 s/m) at 0.5 to 5 m/s. For each speed: the coefficient of
C     restitution, the maximum compression, the peak force, the contact
C     time and the compression time.
C
C     No module, no USE, no INCLUDE: the library's routines are EXTERNAL
C     subroutines called with implicit interfaces (doc/fortran77.md).
C     Build against the installed library with the Makefile next to this
C     file:  make PREFIX=/path/to/prefix  (or with pkg-config).
C
      PROGRAM STEEL
      IMPLICIT NONE
      DOUBLE PRECISION XMASS, C, EN, B, E, BETA
      DOUBLE PRECISION V(6), OUT(8), TABLE(8, 6)
      DOUBLE PRECISION CS(6), ENS(6), BS(6), XMS(6)
      INTEGER I, INFO, ISTAT(6), MAJOR, MINOR, IPATCH
      CHARACTER*80 MSG
      DATA V /0.5D0, 1.0D0, 2.0D0, 3.0D0, 4.0D0, 5.0D0/
C
      XMASS = 0.1D0
      C = 1.7135D10
      EN = 1.5D0
      B = 0.1D0
      CALL HCVERS(MAJOR, MINOR, IPATCH)
      WRITE (*, 100) MAJOR, MINOR, IPATCH
C
C     One impact per call: OUT(1..8) = k, 1 - k**2, rebound velocity,
C     x_max, peak force, compression at the peak, compression time,
C     contact time.
      WRITE (*, 110)
      DO 10 I = 1, 6
         CALL HCIMP(XMASS, C, EN, B, V(I), OUT, INFO)
         IF (INFO .NE. 0) THEN
            WRITE (*, 120) INFO
            IF (INFO .GT. 0) THEN
               CALL HCMSG(INFO, MSG)
               WRITE (*, '(1X, A)') MSG
            END IF
            STOP 1
         END IF
         WRITE (*, 130) V(I), OUT(1), OUT(4), OUT(5), OUT(8), OUT(7)
   10 CONTINUE
C
C     The same table in one call: arrays of contacts, OUT(8, NI).
      DO 20 I = 1, 6
         XMS(I) = XMASS
         CS(I) = C
         ENS(I) = EN
         BS(I) = B
   20 CONTINUE
      CALL HCIMPA(6, XMS, CS, ENS, BS, V, TABLE, ISTAT, INFO)
      IF (INFO .NE. 0) THEN
         WRITE (*, 120) INFO
         STOP 1
      END IF
      WRITE (*, 140) TABLE(1, 6), TABLE(8, 6)
C
C     The damping that gives a restitution of 0.5 at 5 m/s.
      E = 0.5D0
      CALL HCRESI(E, BETA, INFO)
      IF (INFO .NE. 0) THEN
         WRITE (*, 120) INFO
         STOP 1
      END IF
      WRITE (*, 150) E, BETA, BETA / V(6)
C
  100 FORMAT (' hcimpact ', I0, '.', I0, '.', I0,
     &        ': steel ball, m = 0.1 kg, c = 1.7135e10 N/m**1.5,',
     &        ' n = 1.5, b = 0.1 s/m')
  110 FORMAT (/, ' V (m/s)', 8X, 'k', 19X, 'x_max (m)', 15X,
     &        'F_max (N)', 15X, 't_contact (s)', 11X,
     &        't_compression (s)')
  120 FORMAT (' hcimpact failed: INFO = ', I0)
  130 FORMAT (1X, F5.2, 5(1X, 1PE23.16))
  140 FORMAT (/, ' HCIMPA, V = 5 m/s: k = ', 1PE23.16,
     &        ', t_contact = ', 1PE23.16)
  150 FORMAT (' restitution ', F4.2, ': beta = b V = ', 1PE23.16,
     &        ', b = ', 1PE23.16, ' s/m at 5 m/s')
      END
