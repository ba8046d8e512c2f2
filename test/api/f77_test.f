C     SPDX-License-Identifier: Apache-2.0
C
C     Test of the FORTRAN 77 entry points (src/hcimpact/f77/f77.f90) from
C     a fixed-form program with implicit interfaces: values and INFO
C     codes, good and bad arguments (doc/fortran77.md). Exit status 1
C     (STOP 1) if a check fails.
C
      PROGRAM F77TST
      IMPLICIT NONE
      INTEGER NFAIL, NCHECK
      COMMON /CHKCNT/ NFAIL, NCHECK
      DOUBLE PRECISION XMASS, C, EN, B, V, X, XDOT, W, RK, BETA, D, R
      DOUBLE PRECISION OUT(8), VS(6), RKS(6), BETAS(6), ES(3)
      DOUBLE PRECISION OUT9(9), FE(5), FES(5, 2), XE(2), VE(2), F0
      INTEGER ISTE(2)
      DOUBLE PRECISION RKOUT(3)
      DOUBLE PRECISION T(5), XS(5), XDS(5), FS(5), ZERO, XNAN, BIG
      DOUBLE PRECISION XMS(3), CS(3), ENS(3), BS(3), VV(3), TAB(8, 3)
      DOUBLE PRECISION V1A, V2A, EM, CH
      DOUBLE PRECISION CLAW, HCF, HCP, HCD
      EXTERNAL HCF, HCP, HCD
      COMMON /HCLAW/ CLAW
      INTEGER INFO, I, ISTAT(3), MAJOR, MINOR, IPATCH
      CHARACTER*80 MSG
      DATA VS /0.5D0, 1.0D0, 2.0D0, 3.0D0, 4.0D0, 5.0D0/
      DATA RKS /0.9677385785309325D0, 0.93747557994990506D0,
     &          0.88218998624730638D0, 0.83286979226560167D0,
     &          0.78853912590706515D0, 0.74843493159743416D0/
C
      NFAIL = 0
      NCHECK = 0
      ZERO = 0.0D0
C     a quiet NaN without IEEE intrinsics: 0/0 would trap under
C     -ffpe-trap, so take it from the library (HCRES of a negative BETA)
      CALL HCRES(-1.0D0, XNAN, INFO)
      BIG = 1.0D300
      XMASS = 0.1D0
      C = 1.7135D10
      EN = 1.5D0
      B = 0.1D0
C
      CALL HCVERS(MAJOR, MINOR, IPATCH)
      CALL CHKI('HCVERS', 10000*MAJOR + 100*MINOR + IPATCH, 200)
      CALL HCMSG(10, MSG)
      CALL CHKI('HCMSG(10)', INDEX(MSG, 'NULL'), 32)
      CALL HCMSG(99, MSG)
      CALL CHKI('HCMSG(99)', INDEX(MSG, 'unknown'), 1)
C
C     Lambert W
      CALL HCW0(1.0D0, W, INFO)
      CALL CHKI('HCW0 INFO', INFO, 0)
      CALL CHKR('HCW0(1)', W, 0.56714329040978387D0, 1.0D-14)
      CALL HCW0(-1.0D0, W, INFO)
      CALL CHKI('HCW0(-1) INFO', INFO, -1)
      CALL HCWM1(-0.1D0, W, INFO)
      CALL CHKR('HCWM1(-0.1)', W, -3.5771520639572971D0, 1.0D-14)
      CALL HCWM1(0.5D0, W, INFO)
      CALL CHKI('HCWM1(0.5) INFO', INFO, -1)
      CALL HCW0P1(1.0D0, W, INFO)
      CALL CHKR('HCW0P1(1)', W, 0.84140566043696064D0, 1.0D-14)
      CALL HCW0P1(-1.0D0, W, INFO)
      CALL CHKI('HCW0P1(-1) INFO', INFO, -1)
      CALL HCWM1P(1.0D0, W, INFO)
      CALL CHKR('HCWM1P(1)', W, -2.1461932206205826D0, 1.0D-14)
      CALL HCWM1P(XNAN, W, INFO)
      CALL CHKI('HCWM1P(NaN) INFO', INFO, -1)
C
C     Restitution
      CALL HCRES(0.5D0, RK, INFO)
      CALL CHKI('HCRES INFO', INFO, 0)
      CALL CHKR('HCRES(0.5)', RK, 0.74843493159743416D0, 1.0D-14)
      CALL HCRES(-1.0D0, RK, INFO)
      CALL CHKI('HCRES(-1) INFO', INFO, -1)
      CALL HCRESI(0.5D0, BETA, INFO)
      CALL CHKR('HCRESI(0.5)', BETA, 1.4327505332713750D0, 1.0D-14)
      CALL HCRESI(1.5D0, BETA, INFO)
      CALL CHKI('HCRESI(1.5) INFO', INFO, -1)
      CALL HCRESI(ZERO, BETA, INFO)
      CALL CHKI('HCRESI(0) INFO', INFO, -1)
      CALL HCRES1(0.5D0, D, INFO)
      CALL CHKR('HCRES1(0.5)', D, 1.0D0 - 0.74843493159743416D0,
     &          1.0D-14)
      CALL HCRES1(XNAN, D, INFO)
      CALL CHKI('HCRES1(NaN) INFO', INFO, -1)
      CALL HCELOS(0.5D0, R, INFO)
      CALL CHKR('HCELOS(0.5)', R,
     &          1.0D0 - 0.74843493159743416D0**2, 1.0D-14)
      CALL HCELOS(-2.0D0, R, INFO)
      CALL CHKI('HCELOS(-2) INFO', INFO, -1)
      CALL HCRESD(ZERO, D, INFO)
      CALL CHKR('HCRESD(0)', D, -2.0D0/3.0D0, 1.0D-15)
      CALL HCRESD(-1.0D0, D, INFO)
      CALL CHKI('HCRESD(-1) INFO', INFO, -1)
      BETAS(1) = 0.5D0
      BETAS(2) = 0.0D0
      BETAS(3) = -1.0D0
      CALL HCRESA(3, BETAS, RKOUT, INFO)
      CALL CHKI('HCRESA INFO (one bad)', INFO, -2)
      CALL CHKR('HCRESA(1)', RKOUT(1), 0.74843493159743416D0,
     &          1.0D-14)
      CALL CHKR('HCRESA(2)', RKOUT(2), 1.0D0, 0.0D0)
      CALL HCRESA(2, BETAS, RKOUT, INFO)
      CALL CHKI('HCRESA INFO', INFO, 0)
      CALL HCRESA(-1, BETAS, RKOUT, INFO)
      CALL CHKI('HCRESA(N = -1) INFO', INFO, -1)
      CALL HCRESA(0, BETAS, RKOUT, INFO)
      CALL CHKI('HCRESA(N = 0) INFO', INFO, 0)
      ES(1) = 0.5D0
      ES(2) = 1.0D0
      ES(3) = 0.9D0
      CALL HCRSIA(3, ES, BETAS, INFO)
      CALL CHKI('HCRSIA INFO', INFO, 0)
      CALL CHKR('HCRSIA(1)', BETAS(1), 1.4327505332713750D0, 1.0D-14)
      CALL CHKR('HCRSIA(3)', BETAS(3), 0.16648195068530810D0, 1.0D-13)
      ES(2) = 0.0D0
      CALL HCRSIA(3, ES, BETAS, INFO)
      CALL CHKI('HCRSIA INFO (one bad)', INFO, -2)
      CALL HCRSIA(-3, ES, BETAS, INFO)
      CALL CHKI('HCRSIA(N = -3) INFO', INFO, -1)
      CALL HCDAMP(0.5D0, 5.0D0, D, INFO)
      CALL CHKR('HCDAMP(0.5, 5)', D, 1.4327505332713750D0 / 5.0D0,
     &          1.0D-14)
      CALL HCDAMP(1.5D0, 5.0D0, D, INFO)
      CALL CHKI('HCDAMP(E = 1.5) INFO', INFO, -1)
      CALL HCDAMP(0.5D0, -5.0D0, D, INFO)
      CALL CHKI('HCDAMP(V = -5) INFO', INFO, -2)
C
C     Two bodies
      CALL HCHERZ(2.0D11, 0.25D0, 0.01452D0, 2.0D11, 0.25D0, ZERO,
     &            CH, INFO)
      CALL CHKI('HCHERZ INFO', INFO, 0)
      CALL CHKR('HCHERZ', CH, 1.7138D10, 1.0D-4)
      CALL HCHERZ(2.0D11, 0.7D0, 0.01D0, 2.0D11, 0.25D0, ZERO,
     &            CH, INFO)
      CALL CHKI('HCHERZ(PR1 = 0.7) INFO', INFO, -2)
      CALL HCHERZ(2.0D11, 0.25D0, ZERO, 2.0D11, 0.25D0, ZERO,
     &            CH, INFO)
      CALL CHKI('HCHERZ(two plates) INFO', INFO, -6)
      CALL HCHERZ(2.0D11, 0.25D0, 1.0D0, -2.0D11, 0.25D0, ZERO,
     &            CH, INFO)
      CALL CHKI('HCHERZ(E2 < 0) INFO', INFO, -4)
      CALL HCEMAS(1.0D0, 1.0D0, EM, INFO)
      CALL CHKR('HCEMAS', EM, 0.5D0, 1.0D-15)
      CALL HCEMAS(1.0D0, ZERO, EM, INFO)
      CALL CHKI('HCEMAS(M2 = 0) INFO', INFO, -2)
      CALL HCTWOB(1.0D0, 1.0D0, 1.0D0, -1.0D0, 0.5D0, V1A, V2A, INFO)
      CALL CHKI('HCTWOB INFO', INFO, 0)
      CALL CHKR('HCTWOB V1A', V1A, -0.5D0, 1.0D-15)
      CALL CHKR('HCTWOB V2A', V2A, 0.5D0, 1.0D-15)
      CALL HCTWOB(1.0D0, 1.0D0, -1.0D0, 1.0D0, 0.5D0, V1A, V2A, INFO)
      CALL CHKI('HCTWOB(no approach) INFO', INFO, -4)
      CALL HCTWOB(1.0D0, 1.0D0, 1.0D0, -1.0D0, 2.0D0, V1A, V2A, INFO)
      CALL CHKI('HCTWOB(K = 2) INFO', INFO, -5)
      CALL HCTWOB(1.0D0, XNAN, 1.0D0, -1.0D0, 0.5D0, V1A, V2A, INFO)
      CALL CHKI('HCTWOB(M2 = NaN) INFO', INFO, -2)
C
C     Impacts: the seed's table, then each bad argument
      DO 10 I = 1, 6
         CALL HCIMP(XMASS, C, EN, B, VS(I), OUT, INFO)
         CALL CHKI('HCIMP INFO', INFO, 0)
         CALL CHKR('HCIMP k', OUT(1), RKS(I), 1.0D-13)
   10 CONTINUE
      CALL CHKR('HCIMP x_max', OUT(4), 1.1372585556115339D-4, 1.0D-13)
      CALL CHKR('HCIMP F_max', OUT(5), 22315.267380743067D0, 1.0D-13)
      CALL CHKR('HCIMP t_comp', OUT(7), 3.5014163526885175D-5,
     &          1.0D-13)
      CALL CHKR('HCIMP t_contact', OUT(8), 7.7655384043269703D-5,
     &          1.0D-13)
C
C     HCIMPN: the same eight results, then the time of the peak force
      CALL HCIMPN(XMASS, C, EN, B, VS(6), 9, OUT9, INFO)
      CALL CHKI('HCIMPN INFO', INFO, 0)
      DO 15 I = 1, 8
         CALL CHKR('HCIMPN OUT(1..8) = HCIMP', OUT9(I), OUT(I), 0.0D0)
   15 CONTINUE
      IF (.NOT. (OUT9(9) .GT. 0.0D0 .AND. OUT9(9) .LT. OUT(7))) THEN
         CALL CHKI('HCIMPN OUT(9) in (0, t_comp)', 1, 0)
      END IF
      OUT9(2) = -7.0D0
      CALL HCIMPN(XMASS, C, EN, B, VS(6), 1, OUT9, INFO)
      CALL CHKI('HCIMPN(NOUT = 1) INFO', INFO, 0)
      CALL CHKR('HCIMPN(NOUT = 1) k', OUT9(1), RKS(6), 1.0D-13)
      CALL CHKR('HCIMPN(NOUT = 1) OUT(2) untouched', OUT9(2), -7.0D0,
     &          0.0D0)
      CALL HCIMPN(XMASS, C, EN, B, VS(6), 0, OUT9, INFO)
      CALL CHKI('HCIMPN(NOUT = 0) INFO', INFO, -6)
      CALL HCIMPN(XMASS, C, EN, B, VS(6), 10, OUT9, INFO)
      CALL CHKI('HCIMPN(NOUT = 10) INFO', INFO, -6)
      CALL HCIMPN(XMASS, C, 1.0D-20, B, VS(6), 9, OUT9, INFO)
      CALL CHKI('HCIMPN(EN = 1e-20) INFO', INFO, -3)
      CALL CHKN('HCIMPN(EN = 1e-20) OUT', OUT9(9))
C
C     The contact-force element: the steel ball's law at X = 5e-5 m
      F0 = C * (5.0D-5)**1.5D0
      CALL HCFRC(C, EN, B, 5.0D-5, 2.0D0, FE, INFO)
      CALL CHKI('HCFRC INFO', INFO, 0)
      CALL CHKR('HCFRC F', FE(1), F0 * (1.0D0 + B * 2.0D0), 1.0D-14)
      CALL CHKR('HCFRC DFDV', FE(3), B * F0, 1.0D-14)
      CALL CHKR('HCFRC POTENTIAL', FE(4),
     &          C * (5.0D-5)**2.5D0 / 2.5D0, 1.0D-14)
      CALL HCFRC(C, EN, B, 5.0D-5, -20.0D0, FE, INFO)
      CALL CHKI('HCFRC(clamped) INFO', INFO, 0)
      CALL CHKR('HCFRC(clamped) F', FE(1), 0.0D0, 0.0D0)
      CALL CHKR('HCFRC(clamped) dissipation', FE(5),
     &          20.0D0 * F0, 1.0D-14)
      CALL HCFRC(C, 1.0D-7, B, 5.0D-5, 2.0D0, FE, INFO)
      CALL CHKI('HCFRC(EN = 1e-7) INFO', INFO, -2)
      CALL CHKN('HCFRC(EN = 1e-7) F', FE(1))
      CALL HCFRC(C, EN, B, XNAN, 2.0D0, FE, INFO)
      CALL CHKI('HCFRC(X = NaN) INFO', INFO, -4)
      XE(1) = 5.0D-5
      XE(2) = 5.0D-5
      VE(1) = 2.0D0
      VE(2) = 2.0D0
      CS(1) = C
      CS(2) = -C
      ENS(1) = EN
      ENS(2) = EN
      BS(1) = B
      BS(2) = B
      CALL HCFRCA(2, CS, ENS, BS, XE, VE, FES, ISTE, INFO)
      CALL CHKI('HCFRCA INFO', INFO, 2)
      CALL CHKI('HCFRCA ISTAT(2)', ISTE(2), 3)
      CALL CHKR('HCFRCA F(1, 1)', FES(1, 1),
     &          F0 * (1.0D0 + B * 2.0D0), 1.0D-14)
      CALL CHKN('HCFRCA F(1, 2)', FES(1, 2))
      CALL HCFRCP(C, EN, B, 0.02D0, 1.0D0, 1.5D0, 1.02D0 - 5.0D-5,
     &            -0.5D0, FE, INFO)
      CALL CHKI('HCFRCP INFO', INFO, 0)
      CALL CHKR('HCFRCP F', FE(1),
     &          F0 * (1.0D0 + B * 2.0D0), 1.0D-9)
      CALL HCFRCW(C, EN, B, 0.01D0, 1.0D0 + 5.0D-5, 2.0D0, 1.01D0, 1,
     &            FE, INFO)
      CALL CHKI('HCFRCW INFO', INFO, 0)
      CALL CHKR('HCFRCW F', FE(1),
     &          F0 * (1.0D0 + B * 2.0D0), 1.0D-9)
      CALL HCFRCW(C, EN, B, 0.01D0, 1.0D0, 2.0D0, 1.01D0, 0, FE, INFO)
      CALL CHKI('HCFRCW(ISIDE = 0) INFO', INFO, -8)
C
C     The same ball through HCIMPL: the Hertz law as EXTERNAL functions,
C     its constant in COMMON /HCLAW/
      CLAW = C
      CALL HCIMPL(HCF, HCP, HCD, XMASS, B, VS(6), OUT, INFO)
      CALL CHKI('HCIMPL INFO', INFO, 0)
      CALL CHKR('HCIMPL k', OUT(1), RKS(6), 1.0D-13)
      CALL CHKR('HCIMPL F_max', OUT(5), 22315.267380743067D0, 1.0D-12)
      CALL CHKR('HCIMPL t_contact', OUT(8), 7.7655384043269703D-5,
     &          1.0D-12)
      CALL HCIMPL(HCF, HCP, HCD, XMASS, -B, 1.0D0, OUT, INFO)
      CALL CHKI('HCIMPL(B < 0) INFO', INFO, -5)
      CALL CHKN('HCIMPL(B < 0) OUT', OUT(1))
      CALL HCIMPL(HCF, HCP, HCD, XMASS, B, XNAN, OUT, INFO)
      CALL CHKI('HCIMPL(V = NaN) INFO', INFO, -6)
      CLAW = XNAN
      CALL HCIMPL(HCF, HCP, HCD, XMASS, B, 1.0D0, OUT, INFO)
      CALL CHKI('HCIMPL(law gives NaN) INFO', INFO, 13)
      CALL HCIMP(ZERO, C, EN, B, 1.0D0, OUT, INFO)
      CALL CHKI('HCIMP(M = 0) INFO', INFO, -1)
      CALL HCIMP(XMASS, -C, EN, B, 1.0D0, OUT, INFO)
      CALL CHKI('HCIMP(C < 0) INFO', INFO, -2)
      CALL HCIMP(XMASS, C, XNAN, B, 1.0D0, OUT, INFO)
      CALL CHKI('HCIMP(EN = NaN) INFO', INFO, -3)
      CALL HCIMP(XMASS, C, EN, -B, 1.0D0, OUT, INFO)
      CALL CHKI('HCIMP(B < 0) INFO', INFO, -4)
      CALL HCIMP(XMASS, C, EN, B, ZERO, OUT, INFO)
      CALL CHKI('HCIMP(V = 0) INFO', INFO, -5)
      CALL CHKN('HCIMP(V = 0) OUT', OUT(8))
      CALL HCIMP(XMASS, C, EN, BIG, BIG, OUT, INFO)
      CALL CHKI('HCIMP(B V = 1e600) INFO', INFO, 8)
      DO 20 I = 1, 3
         XMS(I) = XMASS
         CS(I) = C
         ENS(I) = EN
         BS(I) = B
         VV(I) = VS(I + 3)
   20 CONTINUE
      CALL HCIMPA(3, XMS, CS, ENS, BS, VV, TAB, ISTAT, INFO)
      CALL CHKI('HCIMPA INFO', INFO, 0)
      CALL CHKR('HCIMPA k(3)', TAB(1, 3), RKS(6), 1.0D-13)
      ENS(2) = -1.0D0
      CALL HCIMPA(3, XMS, CS, ENS, BS, VV, TAB, ISTAT, INFO)
      CALL CHKI('HCIMPA INFO (second bad)', INFO, 2)
      CALL CHKI('HCIMPA ISTAT(2)', ISTAT(2), 4)
      CALL CHKI('HCIMPA ISTAT(3)', ISTAT(3), 0)
      CALL CHKN('HCIMPA OUT(1,2)', TAB(1, 2))
      CALL CHKR('HCIMPA k(3) after a bad one', TAB(1, 3), RKS(6),
     &          1.0D-13)
      CALL HCIMPA(-1, XMS, CS, ENS, BS, VV, TAB, ISTAT, INFO)
      CALL CHKI('HCIMPA(NI = -1) INFO', INFO, -1)
C
C     Velocity at a depth, time law
      V = 5.0D0
      CALL HCIMP(XMASS, C, EN, B, V, OUT, INFO)
      CALL HCVEL(XMASS, C, EN, B, V, ZERO, 1, XDOT, INFO)
      CALL CHKI('HCVEL INFO', INFO, 0)
      CALL CHKR('HCVEL(0, 1)', XDOT, V, 1.0D-14)
      CALL HCVEL(XMASS, C, EN, B, V, ZERO, 2, XDOT, INFO)
      CALL CHKR('HCVEL(0, 2)', XDOT, OUT(3), 1.0D-13)
      X = 2.0D0 * OUT(4)
      CALL HCVEL(XMASS, C, EN, B, V, X, 1, XDOT, INFO)
      CALL CHKI('HCVEL(2 x_max) INFO', INFO, -6)
      CALL HCVEL(XMASS, C, EN, B, V, XNAN, 1, XDOT, INFO)
      CALL CHKI('HCVEL(NaN) INFO', INFO, -6)
      CALL HCVEL(XMASS, C, EN, B, V, ZERO, 3, XDOT, INFO)
      CALL CHKI('HCVEL(IBR = 3) INFO', INFO, -7)
      CALL HCVEL(XMASS, C, EN, B, -V, ZERO, 3, XDOT, INFO)
      CALL CHKI('HCVEL(V < 0) INFO', INFO, -5)
      T(1) = -1.0D0
      T(2) = OUT(7)
      T(3) = 0.5D0 * OUT(8)
      T(4) = 2.0D0 * OUT(8)
      T(5) = 0.0D0
      CALL HCTLAW(XMASS, C, EN, B, V, 5, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTLAW INFO', INFO, 0)
      CALL CHKR('HCTLAW x(t_comp)', XS(2), OUT(4), 1.0D-10)
      CALL CHKR('HCTLAW v(before)', XDS(1), V, 0.0D0)
      CALL CHKR('HCTLAW v(after)', XDS(4), OUT(3), 1.0D-13)
      T(3) = XNAN
      CALL HCTLAW(XMASS, C, EN, B, V, 5, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTLAW(T NaN) INFO', INFO, -7)
      CALL CHKN('HCTLAW(T NaN) X', XS(1))
      CALL HCTLAW(XMASS, C, EN, B, V, -1, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTLAW(NT = -1) INFO', INFO, -6)
      CALL HCTLAW(XMASS, C, ZERO, B, V, 5, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTLAW(EN = 0) INFO', INFO, -3)
      CALL HCTSAM(XMASS, C, EN, B, V, 5, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTSAM INFO', INFO, 0)
      CALL CHKR('HCTSAM T(5)', T(5), OUT(8), 0.0D0)
      CALL CHKR('HCTSAM X(1)', XS(1), 0.0D0, 0.0D0)
      CALL HCTSAM(XMASS, C, EN, B, V, 1, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTSAM(NT = 1) INFO', INFO, -6)
      CALL HCTSAM(-XMASS, C, EN, B, V, 5, T, XS, XDS, FS, INFO)
      CALL CHKI('HCTSAM(M < 0) INFO', INFO, -1)
      CALL CHKN('HCTSAM(M < 0) T', T(1))
C
      IF (NFAIL .NE. 0) THEN
         WRITE (*, '(1X, I0, A, I0, A)') NFAIL, ' of ', NCHECK,
     &      ' checks failed'
         STOP 1
      END IF
      WRITE (*, '(A, I0, A)') ' all ', NCHECK, ' checks passed'
      END
C
C     Check an INTEGER
      SUBROUTINE CHKI(WHAT, IACT, IEXP)
      IMPLICIT NONE
      CHARACTER*(*) WHAT
      INTEGER IACT, IEXP, NFAIL, NCHECK
      COMMON /CHKCNT/ NFAIL, NCHECK
      NCHECK = NCHECK + 1
      IF (IACT .NE. IEXP) THEN
         NFAIL = NFAIL + 1
         WRITE (*, '(A, A, A, I0, A, I0)') ' FAIL ', WHAT, ': got ',
     &      IACT, ', expected ', IEXP
      END IF
      END
C
C     Check a DOUBLE PRECISION within a relative tolerance (NaN fails)
      SUBROUTINE CHKR(WHAT, ACT, EXP, REL)
      IMPLICIT NONE
      CHARACTER*(*) WHAT
      DOUBLE PRECISION ACT, EXP, REL
      INTEGER NFAIL, NCHECK
      COMMON /CHKCNT/ NFAIL, NCHECK
      LOGICAL ISNAN2
      NCHECK = NCHECK + 1
      IF (ISNAN2(ACT)) THEN
         NFAIL = NFAIL + 1
         WRITE (*, '(A, A, A)') ' FAIL ', WHAT, ': got NaN'
      ELSE IF (ABS(ACT - EXP) .GT. REL * ABS(EXP)) THEN
         NFAIL = NFAIL + 1
         WRITE (*, '(A, A, A, 1PE24.17, A, 1PE24.17)') ' FAIL ', WHAT,
     &      ': got ', ACT, ', expected ', EXP
      END IF
      END
C
C     Check that a DOUBLE PRECISION is NaN
      SUBROUTINE CHKN(WHAT, ACT)
      IMPLICIT NONE
      CHARACTER*(*) WHAT
      DOUBLE PRECISION ACT
      INTEGER NFAIL, NCHECK
      COMMON /CHKCNT/ NFAIL, NCHECK
      LOGICAL ISNAN2
      NCHECK = NCHECK + 1
      IF (.NOT. ISNAN2(ACT)) THEN
         NFAIL = NFAIL + 1
         WRITE (*, '(A, A, A, 1PE24.17)') ' FAIL ', WHAT,
     &      ': expected NaN, got ', ACT
      END IF
      END
C
C     NaN test without an ordered comparison (no FP trap): only NaN
C     differs from itself
      LOGICAL FUNCTION ISNAN2(X)
      IMPLICIT NONE
      DOUBLE PRECISION X
      ISNAN2 = .NOT. (X .EQ. X)
      END
C
C     The Hertz law f = CLAW x**1.5 for HCIMPL, its potential and derivative
      DOUBLE PRECISION FUNCTION HCF(X)
      IMPLICIT NONE
      DOUBLE PRECISION X, CLAW
      COMMON /HCLAW/ CLAW
      HCF = CLAW * X**1.5D0
      END
C
      DOUBLE PRECISION FUNCTION HCP(X)
      IMPLICIT NONE
      DOUBLE PRECISION X, CLAW
      COMMON /HCLAW/ CLAW
      HCP = CLAW * X**2.5D0 / 2.5D0
      END
C
      DOUBLE PRECISION FUNCTION HCD(X)
      IMPLICIT NONE
      DOUBLE PRECISION X, CLAW
      COMMON /HCLAW/ CLAW
      HCD = 1.5D0 * CLAW * SQRT(X)
      END
