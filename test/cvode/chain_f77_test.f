C     SPDX-License-Identifier: Apache-2.0
C
C     HCCHN (components/cvode/chain_f77.f90, libhcimpact_cvode) from a
C     fixed-form program with an implicit interface: two balls against
C     the closed forms of one impact (HCEMAS, HCIMP, HCTWOB), three
C     touching balls (momentum, energy, not (0, 0, V)), the contacts
C     table with a leading dimension larger than the rows asked for, and
C     INFO for bad arguments. The bit-for-bit comparison with the
C     Fortran API is test/cvode/test_chain_api.f90. STOP 1 if a check
C     fails.
C
      PROGRAM CHNTST
      IMPLICIT NONE
      INTEGER NBAD
      COMMON /CHNCNT/ NBAD
      INTEGER LDC
      PARAMETER (LDC = 10)
      DOUBLE PRECISION XM(3), V(3), GAP(2), PLAW(3, 2), WALL(4, 2)
      DOUBLE PRECISION OPTS(2), X(3), VF(3), RES(8), CONT(LDC, 7)
      DOUBLE PRECISION OUT(8), EM, V1A, V2A, CPAIR, P0, P1, XNAN
      DOUBLE PRECISION X0(3), V0(3), RES0(8), XINF
      INTEGER IOPTS(4), ICNT(11), ICON(LDC, 2), INFO, I, J, K
      INTEGER ICNT0(11)
      CHARACTER*100 MSG
      CHARACTER*40 WHAT
      CHARACTER*8 SINF
      LOGICAL ISNAN3, SAME
C     +Infinity read from text (an overflow would trap under -ffpe-trap)
      DATA SINF /'Infinity'/
C
      NBAD = 0
C     a quiet NaN from the library (0/0 would trap under -ffpe-trap)
      CALL HCRES(-1.0D0, XNAN, INFO)
      CPAIR = 1.7135D10 / SQRT(2.0D0)
C
C     Two balls, 0.1 and 0.3 kg, at 2 and -0.5 m/s, 0.1 mm apart
      XM(1) = 0.1D0
      XM(2) = 0.3D0
      V(1) = 2.0D0
      V(2) = -0.5D0
      GAP(1) = 1.0D-4
      PLAW(1, 1) = CPAIR
      PLAW(2, 1) = 1.5D0
      PLAW(3, 1) = 0.2D0
      DO 10 I = 1, 4
         WALL(I, 1) = 0.0D0
         WALL(I, 2) = 0.0D0
   10 CONTINUE
      OPTS(1) = 0.0D0
      OPTS(2) = 0.0D0
      DO 20 I = 1, 4
         IOPTS(I) = 0
   20 CONTINUE
      CALL HCCHN(2, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, 3, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('two balls: INFO = 0', INFO .EQ. 0)
      CALL CHECK('two balls: MSG', MSG(1:7) .EQ. 'success')
      CALL CHECK('two balls: one contact, recorded, closed forms',
     &   ICNT(1) .EQ. 1 .AND. ICNT(2) .EQ. 1 .AND. ICNT(3) .EQ. 1
     &   .AND. ICON(1, 1) .EQ. 1 .AND. ICON(1, 2) .EQ. 1)
      CALL HCEMAS(XM(1), XM(2), EM, INFO)
      CALL HCIMP(EM, CPAIR, 1.5D0, 0.2D0, V(1) - V(2), OUT, INFO)
      CALL HCTWOB(XM(1), XM(2), V(1), V(2), OUT(1), V1A, V2A, INFO)
      CALL CLOSE('contact time', CONT(1, 2) - CONT(1, 1), OUT(8),
     &   1.0D-11)
      CALL CLOSE('approach speed', CONT(1, 3), V(1) - V(2), 1.0D-15)
      CALL CLOSE('separation speed', CONT(1, 4), -OUT(3), 1.0D-14)
      CALL CLOSE('peak force', CONT(1, 5), OUT(5), 1.0D-14)
      CALL CLOSE('max deformation', CONT(1, 6), OUT(4), 1.0D-14)
      CALL CLOSE('velocity 1 after', VF(1), V1A, 1.0D-14)
      CALL CLOSE('velocity 2 after', VF(2), V2A, 1.0D-14)
      CALL CHECK('two balls: energy and momentum',
     &   RES(4) .LT. 1.0D-14 .AND. RES(6) .LT. 1.0D-15)
      CALL CHECK('two balls: no rest time', ISNAN3(RES(2)))
C
C     Three touching balls, the first struck at 1 m/s: a cluster
      XM(2) = 0.1D0
      XM(3) = 0.1D0
      V(1) = 1.0D0
      V(2) = 0.0D0
      V(3) = 0.0D0
      GAP(1) = 0.0D0
      GAP(2) = 0.0D0
      PLAW(3, 1) = 0.0D0
      DO 30 I = 1, 3
         PLAW(I, 2) = PLAW(I, 1)
   30 CONTINUE
      OPTS(2) = 1.0D-10
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('cradle: INFO = 0', INFO .EQ. 0)
      P0 = 0.1D0 * 1.0D0
      P1 = 0.1D0 * (VF(1) + VF(2) + VF(3))
      CALL CLOSE('cradle: momentum', P1, P0, 1.0D-14)
      CALL CHECK('cradle: energy to the tolerance', RES(4) .LT. 1.0D-7)
      CALL CHECK('cradle: integrated', ICNT(6) .GE. 1 .AND.
     &   ICNT(7) .GT. 0)
      CALL CHECK('cradle: not (0, 0, V)', ABS(VF(1)) .GT. 1.0D-3 .OR.
     &   ABS(VF(2)) .GT. 1.0D-3)
C
C     Bad arguments: INFO = -i, NaN results
      CALL HCCHN(0, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('N = 0: INFO = -1', INFO .EQ. -1)
      CALL CHECK('N = 0: RES NaN', ISNAN3(RES(1)))
      XM(2) = 0.0D0
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('XM(2) = 0: INFO = -2', INFO .EQ. -2)
      CALL CHECK('XM(2) = 0: X NaN', ISNAN3(X(1)) .AND. ISNAN3(VF(3)))
      XM(2) = 0.1D0
      GAP(2) = -1.0D-9
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('GAP(2) < 0: INFO = -4', INFO .EQ. -4)
      GAP(2) = 0.0D0
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, XNAN, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('GRAV NaN: INFO = -7', INFO .EQ. -7)
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, 5, 4, CONT, ICON, MSG, INFO)
      CALL CHECK('LDC < MAXC: INFO = -15', INFO .EQ. -15)
      IOPTS(1) = 1
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('exact only, a cluster: INFO = 8', INFO .EQ. 8)
      IOPTS(1) = 0
C
C     A MSG shorter than the text is cut (it stopped the program with
C     "End of record"): CHARACTER*80 and *8 for each indexed message
      XM(2) = -1.0D0
      CALL SHORT('XM', -2, XM, V, GAP, PLAW, WALL, OPTS, IOPTS)
      XM(2) = 0.1D0
      V(3) = XNAN
      CALL SHORT('V', -3, XM, V, GAP, PLAW, WALL, OPTS, IOPTS)
      V(3) = 0.0D0
      GAP(1) = -1.0D0
      CALL SHORT('GAP', -4, XM, V, GAP, PLAW, WALL, OPTS, IOPTS)
      GAP(1) = 0.0D0
      PLAW(1, 2) = -1.0D0
      CALL SHORT('PLAW', -5, XM, V, GAP, PLAW, WALL, OPTS, IOPTS)
      PLAW(1, 2) = PLAW(1, 1)
      WALL(1, 2) = -1.0D0
      CALL SHORT('WALL', -6, XM, V, GAP, PLAW, WALL, OPTS, IOPTS)
      WALL(1, 2) = 0.0D0
C
C     An absent wall (WALL(1, K) = 0): the rest of its column is not
C     read, so NaN or an infinity there changes nothing (a NaN gap gave
C     INFO = 1). Each entry alone, then all of both columns at once.
      READ (SINF, *) XINF
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X0, V0,
     &   RES0, ICNT0, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('no walls: INFO = 0', INFO .EQ. 0)
      DO 60 K = 1, 2
         DO 50 I = 2, 4
            DO 40 J = 1, 3
               IF (J .EQ. 1) WALL(I, K) = XNAN
               IF (J .EQ. 2) WALL(I, K) = XINF
               IF (J .EQ. 3) WALL(I, K) = -XINF
               CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS,
     &            IOPTS, X, VF, RES, ICNT, LDC, LDC, CONT, ICON, MSG,
     &            INFO)
               WRITE (WHAT, '(A, I1, A, I1, A, I1)')
     &            'absent wall: WALL(', I, ', ', K, ') case ', J
               CALL CHECK(WHAT, INFO .EQ. 0 .AND. SAME(X, VF, RES, ICNT,
     &            X0, V0, RES0, ICNT0))
               WALL(I, K) = 0.0D0
   40       CONTINUE
   50    CONTINUE
   60 CONTINUE
      DO 70 I = 2, 4
         WALL(I, 1) = XNAN
         WALL(I, 2) = XINF
   70 CONTINUE
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('absent walls, all NaN and Inf: INFO = 0, same',
     &   INFO .EQ. 0 .AND. SAME(X, VF, RES, ICNT, X0, V0, RES0, ICNT0))
      DO 80 I = 1, 4
         WALL(I, 1) = 0.0D0
         WALL(I, 2) = 0.0D0
   80 CONTINUE
C
C     Argument checks as strict as the library's: a tolerance beyond
C     0.01, masses or gaps that add up beyond a quarter of the range of
C     doubles are the argument's INFO < 0 (they gave INFO = 8)
      OPTS(2) = 0.02D0
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('OPTS(2) = 0.02: INFO = -8', INFO .EQ. -8)
      CALL CHECK('OPTS(2) = 0.02: NaN results', ISNAN3(RES(1)) .AND.
     &   ISNAN3(X(1)) .AND. ICNT(1) .EQ. 0)
      CALL CHECK('OPTS(2) = 0.02: MSG', MSG(1:8) .EQ. 'OPTS(2):')
      OPTS(2) = -1.0D-10
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('OPTS(2) < 0: INFO = -8', INFO .EQ. -8)
      OPTS(2) = XNAN
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('OPTS(2) NaN: INFO = -8', INFO .EQ. -8)
      OPTS(2) = 0.01D0
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('OPTS(2) = 0.01: INFO = 0', INFO .EQ. 0)
      OPTS(2) = 1.0D-10
      XM(1) = 1.0D308
      XM(3) = 1.0D308
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('XM adding up beyond: INFO = -2', INFO .EQ. -2)
      XM(1) = 0.1D0
      XM(3) = 0.1D0
      GAP(1) = 1.0D308
      GAP(2) = 1.0D308
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, LDC, LDC, CONT, ICON, MSG, INFO)
      CALL CHECK('GAP adding up beyond: INFO = -4', INFO .EQ. -4)
      GAP(1) = 0.0D0
      GAP(2) = 0.0D0
C
      IF (NBAD .GT. 0) THEN
         WRITE (*, '(I0, A)') NBAD, ' checks failed'
         STOP 1
      END IF
      WRITE (*, '(A)') 'HCCHN: all checks passed'
      END
C
C     Count a failed check
      SUBROUTINE CHECK(WHAT, OK)
      IMPLICIT NONE
      CHARACTER*(*) WHAT
      LOGICAL OK
      INTEGER NBAD
      COMMON /CHNCNT/ NBAD
      IF (.NOT. OK) THEN
         NBAD = NBAD + 1
         WRITE (*, '(2A)') ' FAIL ', WHAT
      END IF
      END
C
C     HCCHN with a bad argument and MSG of 100, 80 and 8 characters:
C     INFO = IEXP each time, the text starts with WHAT, the shorter ones
C     are the longer cut
      SUBROUTINE SHORT(WHAT, IEXP, XM, V, GAP, PLAW, WALL, OPTS, IOPTS)
      IMPLICIT NONE
      CHARACTER*(*) WHAT
      INTEGER IEXP, IOPTS(4)
      DOUBLE PRECISION XM(3), V(3), GAP(2), PLAW(3, 2), WALL(4, 2)
      DOUBLE PRECISION OPTS(2), X(3), VF(3), RES(8), CONT(1, 7)
      INTEGER ICNT(11), ICON(1, 2), INFO, INFO80, INFO8
      CHARACTER*100 MSG
      CHARACTER*80 MSG80
      CHARACTER*8 MSG8
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, 1, 1, CONT, ICON, MSG, INFO)
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, 1, 1, CONT, ICON, MSG80, INFO80)
      CALL HCCHN(3, XM, V, GAP, PLAW, WALL, 0.0D0, OPTS, IOPTS, X, VF,
     &   RES, ICNT, 1, 1, CONT, ICON, MSG8, INFO8)
      CALL CHECK(WHAT // ': INFO', INFO .EQ. IEXP .AND.
     &   INFO80 .EQ. IEXP .AND. INFO8 .EQ. IEXP)
      CALL CHECK(WHAT // ': MSG', MSG(1:LEN(WHAT) + 1) .EQ. WHAT // '('
     &   .AND. LEN_TRIM(MSG) .LT. LEN(MSG))
      CALL CHECK(WHAT // ': MSG cut', MSG80 .EQ. MSG(1:80) .AND.
     &   MSG8 .EQ. MSG(1:8))
      END
C
C     Whether two runs gave the same outputs, bit for bit (NaN as NaN)
      LOGICAL FUNCTION SAME(X, VF, RES, ICNT, X0, V0, RES0, ICNT0)
      IMPLICIT NONE
      DOUBLE PRECISION X(3), VF(3), RES(8), X0(3), V0(3), RES0(8)
      INTEGER ICNT(11), ICNT0(11), I
      LOGICAL ISNAN3, EQ
      INTEGER J
      EQ(J) = RES(J) .EQ. RES0(J) .OR. (ISNAN3(RES(J)) .AND.
     &   ISNAN3(RES0(J)))
      SAME = .TRUE.
      DO 10 I = 1, 3
         SAME = SAME .AND. X(I) .EQ. X0(I) .AND. VF(I) .EQ. V0(I)
   10 CONTINUE
      DO 20 I = 1, 8
         SAME = SAME .AND. EQ(I)
   20 CONTINUE
      DO 30 I = 1, 11
         SAME = SAME .AND. ICNT(I) .EQ. ICNT0(I)
   30 CONTINUE
      END
C
C     ACT within REL of EXP (NaN fails)
      SUBROUTINE CLOSE(WHAT, ACT, EXP, REL)
      IMPLICIT NONE
      CHARACTER*(*) WHAT
      DOUBLE PRECISION ACT, EXP, REL
      LOGICAL ISNAN3
      IF (ISNAN3(ACT)) THEN
         CALL CHECK(WHAT, .FALSE.)
      ELSE
         IF (ABS(ACT - EXP) .GT. REL * ABS(EXP))
     &      WRITE (*, '(A, 2E26.17)') ' got, expected: ', ACT, EXP
         CALL CHECK(WHAT, ABS(ACT - EXP) .LE. REL * ABS(EXP))
      END IF
      END
C
C     NaN without an ordered comparison: only NaN differs from itself
      LOGICAL FUNCTION ISNAN3(X)
      IMPLICIT NONE
      DOUBLE PRECISION X
      ISNAN3 = .NOT. (X .EQ. X)
      END
