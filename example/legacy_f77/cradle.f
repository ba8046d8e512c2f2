C     SPDX-License-Identifier: Apache-2.0
C
C     A legacy FORTRAN 77 program with its own integrator: three equal
C     steel balls on a line (a Newton's cradle), the first striking the
C     other two, which touch. The program steps the motion with the
C     classical fourth-order Runge-Kutta method at a fixed step, as a
C     multibody code does, and takes each contact force from the
C     library's contact-force element HCFRCP (two bodies from their
C     positions and velocities: the force, its derivatives, the elastic
C     energy and the dissipated power; doc/contact-force.md).
C
C     It checks itself twice:
C     1. one ball against a wall (HCFRCW), integrated the same way: its
C        rebound speed and contact time against the closed forms of one
C        impact (HCIMP);
C     2. the cradle: kinetic + elastic + dissipated energy stays the
C        initial kinetic energy, momentum is conserved, and the three
C        touching balls do not end at (0, 0, V) as the classical
C        instantaneous collisions would have them.
C     It stops with a non-zero status when a check fails.
C
C     Build against the installed library: make cradle (Makefile).
C
      PROGRAM CRADLE
      IMPLICIT NONE
      INTEGER NB, NS
      PARAMETER (NB = 3, NS = 2 * NB + 1)
      DOUBLE PRECISION XMASS, R, C, EN, B, V0
      DOUBLE PRECISION Y(NS), Y0(NS), DY(NS), K1(NS), K2(NS), K3(NS)
      DOUBLE PRECISION K4(NS), OUT(8), H, T, TC, E0, E, P0, P, WORST
      DOUBLE PRECISION VMAX, EPOT
      INTEGER I, J, INFO, ISTEP, NFAIL
      COMMON /BALLS/ XMASS, R, C, EN, B
      EXTERNAL RATE, RATEW, ENERGY
      DOUBLE PRECISION ENERGY
C
C     Steel balls of radius 1.452 cm, 0.1 kg, the seed's Hertz constant
C     halved for two equal balls of steel (c of a sphere on a plate
C     with R replaced by R/2), damping 0.1 s/m; the first at 1 m/s.
      XMASS = 0.1D0
      R = 1.452D-2
      C = 1.7135D10 / SQRT(2.0D0)
      EN = 1.5D0
      B = 0.1D0
      V0 = 1.0D0
      NFAIL = 0
C
C     1. One ball against a wall on its right, touching it at t = 0
      CALL HCIMP(XMASS, 1.7135D10, EN, B, V0, OUT, INFO)
      IF (INFO .NE. 0) STOP 2
      TC = OUT(8)
      H = TC / 4000.0D0
      Y(1) = 0.0D0
      Y(2) = V0
      Y(3) = 0.0D0
      T = 0.0D0
      DO 10 ISTEP = 1, 8000
         CALL RK4(RATEW, 3, Y, H, DY, K1, K2, K3, K4, Y0)
         T = T + H
         IF (Y(1) .LE. 0.0D0) GO TO 11
   10 CONTINUE
   11 CONTINUE
C     the end of contact between the last two steps, linearly
      T = T - H * Y(1) / (Y(1) - Y0(1))
      WRITE (*, 100) -Y(2) / V0, OUT(1), T, TC
  100 FORMAT (' one ball on a wall:  rebound/V =', F12.8,
     &        '  closed form k =', F12.8 /
     &        '                      contact time =', ES13.6,
     &        '  closed form =', ES13.6)
      IF (ABS(-Y(2) / V0 - OUT(1)) .GT. 1.0D-6) NFAIL = NFAIL + 1
      IF (ABS(T - TC) .GT. 1.0D-3 * TC) NFAIL = NFAIL + 1
C
C     2. The cradle: centres 2R apart (touching), ball 1 moving
      DO 20 I = 1, NB
         Y(I) = 2.0D0 * R * DBLE(I - 1)
         Y(NB + I) = 0.0D0
   20 CONTINUE
      Y(NB + 1) = V0
      Y(NS) = 0.0D0
      E0 = ENERGY(Y)
      P0 = 0.0D0
      DO 25 I = 1, NB
         P0 = P0 + XMASS * Y(NB + I)
   25 CONTINUE
      WORST = 0.0D0
      H = TC / 4000.0D0
      DO 30 ISTEP = 1, 200000
         CALL RK4(RATE, NS, Y, H, DY, K1, K2, K3, K4, Y0)
         E = ENERGY(Y)
         WORST = MAX(WORST, ABS(E - E0) / E0)
C        done when no pair overlaps and none approaches
         DO 28 J = 1, NB - 1
            IF (Y(J + 1) - Y(J) .LT. 2.0D0 * R) GO TO 30
            IF (Y(NB + J) .GT. Y(NB + J + 1)) GO TO 30
   28    CONTINUE
         GO TO 31
   30 CONTINUE
   31 CONTINUE
      P = 0.0D0
      VMAX = 0.0D0
      EPOT = 0.0D0
      DO 35 I = 1, NB
         P = P + XMASS * Y(NB + I)
         VMAX = MAX(VMAX, ABS(Y(NB + I)))
   35 CONTINUE
      WRITE (*, 110) (Y(NB + I) / V0, I = 1, NB)
  110 FORMAT (' three touching balls, final velocities / V:', 3F11.6)
      WRITE (*, 120) WORST, ABS(P - P0) / P0, Y(NS) / E0
  120 FORMAT (' energy balance error', ES10.2, ', momentum error',
     &        ES10.2, ', share of energy dissipated', F9.5)
      IF (WORST .GT. 1.0D-9) NFAIL = NFAIL + 1
      IF (ABS(P - P0) .GT. 1.0D-12 * P0) NFAIL = NFAIL + 1
C     not the instantaneous answer (0, 0, V): ball 2 keeps moving
      IF (ABS(Y(NB + 2)) .LT. 1.0D-3 * V0) NFAIL = NFAIL + 1
      IF (NFAIL .NE. 0) THEN
         WRITE (*, '(A, I2, A)') ' FAILED:', NFAIL, ' check(s)'
         STOP 1
      END IF
      WRITE (*, '(A)') ' all checks passed'
      END
C
C     One step of the classical Runge-Kutta method for Y' = F(Y) (F a
C     subroutine F(Y, DY)); Y0 keeps the state before the step.
      SUBROUTINE RK4(F, N, Y, H, DY, K1, K2, K3, K4, Y0)
      IMPLICIT NONE
      INTEGER N, I
      DOUBLE PRECISION Y(N), H, DY(N), K1(N), K2(N), K3(N), K4(N), Y0(N)
      EXTERNAL F
      DO 10 I = 1, N
         Y0(I) = Y(I)
   10 CONTINUE
      CALL F(Y0, K1)
      DO 20 I = 1, N
         DY(I) = Y0(I) + 0.5D0 * H * K1(I)
   20 CONTINUE
      CALL F(DY, K2)
      DO 30 I = 1, N
         DY(I) = Y0(I) + 0.5D0 * H * K2(I)
   30 CONTINUE
      CALL F(DY, K3)
      DO 40 I = 1, N
         DY(I) = Y0(I) + H * K3(I)
   40 CONTINUE
      CALL F(DY, K4)
      DO 50 I = 1, N
         Y(I) = Y0(I) + H / 6.0D0 * (K1(I) + 2.0D0 * K2(I)
     &          + 2.0D0 * K3(I) + K4(I))
   50 CONTINUE
      END
C
C     The cradle: Y = positions, velocities, dissipated energy.
      SUBROUTINE RATE(Y, DY)
      IMPLICIT NONE
      INTEGER NB
      PARAMETER (NB = 3)
      DOUBLE PRECISION Y(2 * NB + 1), DY(2 * NB + 1), F(5)
      DOUBLE PRECISION XMASS, R, C, EN, B
      INTEGER I, INFO
      COMMON /BALLS/ XMASS, R, C, EN, B
      DO 10 I = 1, NB
         DY(I) = Y(NB + I)
         DY(NB + I) = 0.0D0
   10 CONTINUE
      DY(2 * NB + 1) = 0.0D0
      DO 20 I = 1, NB - 1
         CALL HCFRCP(C, EN, B, 2.0D0 * R, Y(I), Y(NB + I), Y(I + 1),
     &               Y(NB + I + 1), F, INFO)
         IF (INFO .NE. 0) STOP 3
C        +F on the right ball, -F on the left one
         DY(NB + I) = DY(NB + I) - F(1) / XMASS
         DY(NB + I + 1) = DY(NB + I + 1) + F(1) / XMASS
         DY(2 * NB + 1) = DY(2 * NB + 1) + F(5)
   20 CONTINUE
      END
C
C     One ball (position of its surface, velocity, dissipated energy)
C     against a wall at 0 on its right: the sphere-on-plate constant.
      SUBROUTINE RATEW(Y, DY)
      IMPLICIT NONE
      DOUBLE PRECISION Y(3), DY(3), F(5)
      DOUBLE PRECISION XMASS, R, C, EN, B
      INTEGER INFO
      COMMON /BALLS/ XMASS, R, C, EN, B
      CALL HCFRCW(1.7135D10, EN, B, 0.0D0, Y(1), Y(2), 0.0D0, 1, F,
     &            INFO)
      IF (INFO .NE. 0) STOP 4
C     the force on the body is -ISIDE F(1)
      DY(1) = Y(2)
      DY(2) = -F(1) / XMASS
      DY(3) = F(5)
      END
C
C     Kinetic + elastic + dissipated energy of the cradle (J).
      DOUBLE PRECISION FUNCTION ENERGY(Y)
      IMPLICIT NONE
      INTEGER NB
      PARAMETER (NB = 3)
      DOUBLE PRECISION Y(2 * NB + 1), F(5)
      DOUBLE PRECISION XMASS, R, C, EN, B
      INTEGER I, INFO
      COMMON /BALLS/ XMASS, R, C, EN, B
      ENERGY = Y(2 * NB + 1)
      DO 10 I = 1, NB
         ENERGY = ENERGY + 0.5D0 * XMASS * Y(NB + I)**2
   10 CONTINUE
      DO 20 I = 1, NB - 1
         CALL HCFRCP(C, EN, B, 2.0D0 * R, Y(I), Y(NB + I), Y(I + 1),
     &               Y(NB + I + 1), F, INFO)
         ENERGY = ENERGY + F(4)
   20 CONTINUE
      END
