//! A synthetic WITSML 1.4.1.1 trajectory in the style of the Schlumberger files of the Volve
//! data set (pretty-printed, angles in `dega`, toolfaces, raw sensor data, corrections,
//! uncertainties and validation values on every station: about 2.5 kB a station), for the
//! reader's benchmark (`benches/witsml.rs`) and tests.

use std::fmt::Write;

/// A trajectory of `stations` stations, 30 m apart from a tie-in at MD 0: vertical to 300 m,
/// then a build of 1.5 deg/30 m to 60 deg, turning 0.5 deg/30 m from azimuth 110 deg. About
/// 480 stations make 1.2 MB.
pub fn synthetic_trajectory(stations: usize) -> String {
    let mut s = String::with_capacity(2600 * stations + 2000);
    s.push_str(concat!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n",
        "<trajectorys xmlns=\"http://www.witsml.org/schemas/1series\" version=\"1.4.1.1\">\n",
        "<trajectory uidWell=\"W-1\" uidWellbore=\"B-1\" uid=\"T-1\">\n",
        "<nameWell>synthetic</nameWell>\n<nameWellbore>synthetic - main wellbore</nameWellbore>\n",
        "<name>synthetic MWD survey</name>\n<serviceCompany>example</serviceCompany>\n",
        "<magDeclUsed uom=\"dega\">-2.21</magDeclUsed>\n<gridCorUsed uom=\"dega\">-0.95</gridCorUsed>\n",
        "<aziRef>grid north</aziRef>\n",
    ));
    for k in 0..stations {
        let md = 30.0 * k as f64;
        let incl = ((md - 300.0).max(0.0) * 1.5 / 30.0).min(60.0);
        let azi = 110.0 + md * 0.5 / 30.0;
        let kind = if k == 0 { "tie in point" } else { "magnetic MWD" };
        let _ = write!(
            s,
            concat!(
                "<trajectoryStation uid=\"S-{k}\">\n",
                "<dTimStn>2007-11-16T04:43:28.000Z</dTimStn>\n<typeTrajStation>{kind}</typeTrajStation>\n",
                "<md uom=\"m\">{md}</md>\n<tvd uom=\"m\">0</tvd>\n<incl uom=\"dega\">{incl:.2}</incl>\n<azi uom=\"dega\">{azi:.2}</azi>\n",
                "<mtf uom=\"dega\">19.542</mtf>\n<gtf uom=\"dega\">-162.474</gtf>\n",
                "<dispNs uom=\"m\">0</dispNs>\n<dispEw uom=\"m\">0</dispEw>\n<vertSect uom=\"m\">0</vertSect>\n",
                "<dls uom=\"dega/m\">0.0378280839895013</dls>\n<rateTurn uom=\"dega/m\">0.0166666666666667</rateTurn>\n",
                "<rateBuild uom=\"dega/m\">0.05</rateBuild>\n<mdDelta uom=\"m\">30</mdDelta>\n<tvdDelta uom=\"m\">29.9</tvdDelta>\n",
                "<gravTotalUncert uom=\"m/s2\">0.024384</gravTotalUncert>\n<dipAngleUncert uom=\"dega\">0.45</dipAngleUncert>\n",
                "<magTotalUncert uom=\"nT\">300</magTotalUncert>\n<gravAccelCorUsed>false</gravAccelCorUsed>\n",
                "<magXAxialCorUsed>true</magXAxialCorUsed>\n<sagCorUsed>false</sagCorUsed>\n<magDrlstrCorUsed>false</magDrlstrCorUsed>\n",
                "<gravTotalFieldReference uom=\"m/s2\">9.8246184</gravTotalFieldReference>\n",
                "<magTotalFieldReference uom=\"nT\">50360.501</magTotalFieldReference>\n",
                "<magDipAngleReference uom=\"dega\">71.63</magDipAngleReference>\n<statusTrajStation>position</statusTrajStation>\n",
                "<rawData>\n<gravAxialRaw uom=\"m/s2\">9.8261424</gravAxialRaw>\n<gravTran1Raw uom=\"m/s2\">0.0932688</gravTran1Raw>\n",
                "<gravTran2Raw uom=\"m/s2\">-0.0295656</gravTran2Raw>\n<magAxialRaw uom=\"nT\">48800</magAxialRaw>\n",
                "<magTran1Raw uom=\"nT\">10176</magTran1Raw>\n<magTran2Raw uom=\"nT\">-3840</magTran2Raw>\n</rawData>\n",
                "<corUsed>\n<gravAxialAccelCor uom=\"m/s2\">0</gravAxialAccelCor>\n<gravTran1AccelCor uom=\"m/s2\">0</gravTran1AccelCor>\n",
                "<gravTran2AccelCor uom=\"m/s2\">0</gravTran2AccelCor>\n<magAxialDrlstrCor uom=\"nT\">0</magAxialDrlstrCor>\n",
                "<magTran1DrlstrCor uom=\"nT\">0</magTran1DrlstrCor>\n<magTran2DrlstrCor uom=\"nT\">0</magTran2DrlstrCor>\n",
                "<sagIncCor uom=\"dega\">0</sagIncCor>\n<sagAziCor uom=\"dega\">0</sagAziCor>\n",
                "<stnMagDeclUsed uom=\"dega\">-2.23</stnMagDeclUsed>\n<stnGridCorUsed uom=\"dega\">-0.95</stnGridCorUsed>\n",
                "<dirSensorOffset uom=\"m\">28.2400248</dirSensorOffset>\n</corUsed>\n",
                "<valid>\n<magTotalFieldCalc uom=\"nT\">49997.366</magTotalFieldCalc>\n<magDipAngleCalc uom=\"dega\">78.004</magDipAngleCalc>\n",
                "<gravTotalFieldCalc uom=\"m/s2\">9.826752</gravTotalFieldCalc>\n</valid>\n",
                "<commonData>\n<dTimCreation>2014-05-26T17:06:59.204Z</dTimCreation>\n<dTimLastChange>2014-05-26T17:06:59.204Z</dTimLastChange>\n",
                "<priv_userOwner>someone@example.com</priv_userOwner>\n<priv_dTimReceived>2014-05-26T17:06:59.204Z</priv_dTimReceived>\n</commonData>\n",
                "</trajectoryStation>\n"
            ),
            k = k,
            kind = kind,
            md = md,
            incl = incl,
            azi = azi,
        );
    }
    s.push_str("</trajectory>\n</trajectorys>\n");
    s
}
