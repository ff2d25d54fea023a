#pragma once
// Embedded Runge-Kutta-Nystrom pairs with step-size control, for q'' = F(q):
// dq/dt = M^-1 p, dp/dt = F(q). Not symplectic: for short, very accurate runs
// (an orbit to 1e-12 over a few periods), not for long ones, where the
// splitting methods keep the energy bounded and these do not.
//
// An s-stage RKN pair (Hairer, Norsett & Wanner, Solving ODE I, sect. II.14,
// eq. 14.8) with forces k_i = F(Q_i) and accelerations u_i = M^-1 k_i:
//     Q_i     = q + c_i h v + h^2 sum_j a_ij u_j          (v = M^-1 p)
//     q_new   = q + h v + h^2 sum_i b_i u_i,   p_new = p + h sum_i bp_i k_i,
// and the embedded pair (b_hat, bp_hat) of lower order gives the error
// estimate; the step goes on with the higher order (local extrapolation).
// Because the positions are built from accelerations, M^-1 must be linear:
// velocity(p) of the Hamiltonian must be linear in p (T quadratic). The
// stepper checks that once, on its first step (velocity(p + F) against
// velocity(p) + velocity(F), and velocity(2p) against 2 velocity(p)), and
// refuses a kinetic energy that fails, such as the relativistic pendulum's;
// a non-linearity that these probes cannot see is not detected.
//
// The pairs (each a table of published coefficients, cited there):
//   dprkn6  6(4), 6 stages, FSAL, with a continuous extension of order 6 in q (5 in p)
//   dprkn8  8(6), 9 stages, FSAL
//   dprkn12 12(10), 17 stages
// FSAL (first same as last): the last stage is evaluated at c = 1 with the
// weights b, so its force is F(q_new) and the next step's first force is
// reused: s - 1 forces per step. The stepper keeps the last force with the q
// it belongs to and reuses it whenever it is handed that q again (the next
// step, or a retry after a rejected step), so handing it any state is safe.
//
// Coefficients are kept as text, exact rationals "p/q" where published so,
// decimals with 40 digits otherwise, and converted once to the stepper's
// scalar: the same table serves double, long double and 113-bit numbers.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "../core/error.hpp"
#include "../core/hamiltonian.hpp"
#include "../core/integrate.hpp"
#include "../core/phase_space.hpp"

namespace sympl {

// Dormand & Prince (1987), "Runge-Kutta-Nystrom triples", Comput. Math. Appl.
// 13(12), 937-949: the triple RKN6(4)6FD, with R = sqrt(8581):
//   c2 = (209 - R)/900, c3 = 2 c2, c4 = (209 + R)/450, c5 = 9/10, c6 = 1;
//   e.g. a21 = (26131 - 209R)/810000, b3 = (84119543 + 366727R)/409622616,
//   b_hat1 = (2701 + 23R)/4563, bp3 = (389225579 + 96856R)/1024056540.
// The irrational entries below are those closed forms evaluated to 40 digits;
// the dense-output weights b_i(theta) = sum_k b_dense[i][k] theta^k give
// q(t + theta h) = q + theta h v + (theta h)^2 sum_i b_i(theta) u_i and
// p(t + theta h) = p + theta h sum_i bp_i(theta) k_i.
struct dprkn6 {
    static constexpr const char* name = "dprkn6";
    static constexpr int stages = 6, order = 6, embedded_order = 4;
    static constexpr std::array<const char*, 6> c = {
        "0", "0.1292959031367044152889900532090456452754", "0.2585918062734088305779801064180912905508",
        "0.6702970826154800583109087824707975983381", "9/10", "1"
    };
    // a_ij, j < i, row by row (row i on its own line(s)):
    static constexpr std::array<const char*, 15> a = {
        "0.008358715283968025328221023467433933180618",
        "0.01114495371195736710429469795657857757416", "0.02228990742391473420858939591315715514832",
        "0.1454747428010917858959352323159686240192", "-0.2298606405226474731202614562969686361279",
        "0.3090349872029675365287260807285482300035",
        "-0.2076682629507899543351462052518642381387", "0.6863667842925143122735718510417348831938",
        "-0.199549277872349252201326358887628006266", "0.1258507565306248942629007130977573612108",
        "329/4212", "0", "0.2882917411897667776841772093001956851928", "0.122425537174570410182422422005317973262",
        "200/17901"
    };
    static constexpr std::array<const char*, 6> b = {
        "329/4212", "0", "0.2882917411897667776841772093001956851928", "0.122425537174570410182422422005317973262",
        "200/17901", "0"
    };
    static constexpr std::array<const char*, 6> b_hat = {
        "1.058859260370418278220010058858811120491", "-2.406751371924452053191767776315309930093",
        "1.847892111554033774971757717456498809603", "0", "0", "0"
    };
    static constexpr std::array<const char*, 6> bp = {
        "329/4212", "0", "0.3888434787059826027159522085233166983955",
        "0.3713207579288422674030355575232728776059", "2000/17901", "1/20"
    };
    static constexpr std::array<const char*, 6> bp_hat = {
        "115/2106", "0", "0.4612667859036268442946835348803130963085",
        "0.1958808594793126562918758752085087572193", "6950/17901", "-1/10"
    };
    static constexpr std::array<std::array<const char*, 5>, 6> b_dense = {{
        {"1/2", "-437/351", "3193/2106", "-1273/1404", "25/117"},
        {"0", "0", "0", "0", "0"},
        {"0", "1.985937198870503198511884407608657312101", "-3.577652872294920943852756125939620150387",
         "2.538401116410950355558970076331125777234", "-0.6583937017967658325339211486999672537545"},
        {"0", "-1.855935827692661432434824212901403781318", "5.547586751052329113025631181167616554854",
         "-5.164133553908093735055290749122386803789", "1.594908167722996464646906202861492003515"},
        {"0", "1000/459", "-124000/17901", "43400/5967", "-5000/1989"},
        {"0", "-117/110", "757/220", "-823/220", "15/11"},
    }};
    static constexpr std::array<std::array<const char*, 5>, 6> bp_dense = {{
        {"1", "-437/117", "6386/1053", "-6365/1404", "50/39"},
        {"0", "0", "0", "0", "0"},
        {"0", "5.957811596611509595535653222825971936302", "-14.31061148917968377541102450375848060155",
         "12.69200558205475177779485038165562888617", "-3.950362210780594995203526892199803522527"},
        {"0", "-5.567807483077984297304472638704211343953", "22.19034700420931645210252472467046621942",
         "-25.82066776954046867527645374561193401894", "9.569449006337978787881437217168952021087"},
        {"0", "1000/153", "-496000/17901", "217000/5967", "-10000/663"},
        {"0", "-351/110", "757/55", "-823/44", "90/11"},
    }};
};

// Dormand, El-Mikkawy & Prince (1987), "High-order embedded Runge-Kutta-Nystrom
// formulae", IMA J. Numer. Anal. 7, 423-430: RKN8(6)9FM. Exact rationals.
struct dprkn8 {
    static constexpr const char* name = "dprkn8";
    static constexpr int stages = 9, order = 8, embedded_order = 6;
    static constexpr std::array<const char*, 9> c = {
        "0", "1/20", "1/10", "3/10", "1/2", "7/10", "9/10", "1", "1"
    };
    // a_ij, j < i, row by row (row i on its own line(s)):
    static constexpr std::array<const char*, 36> a = {
        "1/800",
        "1/600", "1/300",
        "9/200", "-9/100", "9/100",
        "-66701/197352", "28325/32892", "-2665/5482", "2170/24669",
        "227015747/304251000", "-54897451/30425100", "12942349/10141700", "-9499/304251", "539/9250",
        "-1131891597/901789000", "41964921/12882700", "-6663147/3220675", "270954/644135", "-108/5875", "114/1645",
        "13836959/3667458", "-17731450/1833729", "1063919505/156478208", "-33213845/39119552", "13335/28544",
        "-705/14272", "1645/57088",
        "223/7938", "0", "1175/8064", "925/6048", "41/448", "925/14112", "1175/72576", "0"
    };
    static constexpr std::array<const char*, 9> b = {
        "223/7938", "0", "1175/8064", "925/6048", "41/448", "925/14112", "1175/72576", "0", "0"
    };
    static constexpr std::array<const char*, 9> b_hat = {
        "7987313/109941300", "0", "1610737/44674560", "10023263/33505920", "-497221/12409600", "10023263/78180480",
        "1610737/402071040", "0", "0"
    };
    static constexpr std::array<const char*, 9> bp = {
        "223/7938", "0", "5875/36288", "4625/21168", "41/224", "4625/21168", "5875/36288", "223/7938", "0"
    };
    static constexpr std::array<const char*, 9> bp_hat = {
        "7987313/109941300", "0", "1610737/40207104", "10023263/23454144", "-497221/6204800", "10023263/23454144",
        "1610737/40207104", "-4251941/54970650", "3/20"
    };
};

// Dormand, El-Mikkawy & Prince (1987), IMA J. Numer. Anal. 7, 423-430:
// RKN12(10)17M, 17 stages, not FSAL (its stage 17 is not q_new). Rationals as
// in the public table of the coefficients; those of rows 14 to 17 satisfy
// sum_j a_ij = c_i^2 / 2 to 1e-53 only (a rationalization of the published
// numbers, far below any precision used here).
struct dprkn12 {
    static constexpr const char* name = "dprkn12";
    static constexpr int stages = 17, order = 12, embedded_order = 10;
    static constexpr std::array<const char*, 17> c = {
        "0", "1/50", "1/25", "1/10", "2/15", "4/25", "1/20", "1/5", "1/4", "1/3", "1/2", "5/9", "3/4", "6/7",
        "8437/8926", "1", "1"
    };
    // a_ij, j < i, row by row (row i on its own line(s)):
    static constexpr std::array<const char*, 136> a = {
        "1/5000",
        "1/3750", "1/1875",
        "7/2400", "-1/240", "1/160",
        "2/1215", "0", "4/729", "32/18225",
        "152/78125", "0", "1408/196875", "2048/703125", "432/546875",
        "29/51200", "0", "341/387072", "-151/345600", "243/716800", "-11/110592",
        "37/12000", "0", "0", "2/1125", "27/10000", "5/3168", "224/20625",
        "100467472123373/27511470744477696", "0", "101066550784375/25488568483854336",
        "49478218404275/15475202293768704", "21990175014231/2674726322379776",
        "-3576386017671875/2723635603703291904", "16163228153/1654104722787", "38747524076705/10316801529179136",
        "62178936641284701329/16772293867250014666848", "0", "46108564356250/9072835168325103",
        "1522561724950/1296119309760729", "-45978886013453735443/2174186242050927827184",
        "299403512366617849203125/4981371278573254356053856", "15571226634087127616/774466927638876610083",
        "-133736375367792139885/4717207650164066625051", "7461389216/501451974639",
        "501256914705531962342417557181/14270506505142656332600844507392", "0", "-1143766215625/132752960853408",
        "-6864570325/1185294293334", "194348369382310456605879163404183/99893545535998594328205911551744",
        "-94634958447010580589908066176109375/27549212808177898050085930321520256",
        "-17006472665356285286219618514/155584463413110817059022733377",
        "33530528814694461893884349656345/14270506505142656332600844507392",
        "-13439782155791134368/17777268379678341919", "1441341768767571/13159456712985856",
        "105854110734231079069010159870911189747853/5156624149476760916008179453333467046288864", "0",
        "-144579793509250000/19842290513127000261", "-101935644099967250/48188419817594143491",
        "1585474394319811696785932424388196965/1709257457318830856936350991091849456",
        "-843499776333774172853009613469456309715703125/510505790798199330684809765880013237582597536",
        "-15057703799298260121553794369056896088480/714327132646734138085088291809720015274157",
        "1749840442221344572962864758990584360232600/1450300542040339007627300471250037606768743",
        "-11255775246405733991656178432768/27206626483067760480757659602193",
        "669010348769579696/7368057640845834597", "4598083098752/858563707934367",
        "-1639758773684715326849438048667467886824967397/11447568726280607813664651120965112496134881280", "0",
        "3942453384375/314673684985856", "11737114158175/1719466921529856",
        "-23710715033675876683332701739887457/4940189888325748664958546898558976",
        "498150575499633273684774666731162498301909124515625/87415924307623977386706008889913792042985180430336",
        "64881557768202140428371179540010005713998551/85896810580242200654071863296887242202224768",
        "-2336309182318568698279006266321563486172654055/18316109962048972501863441793544179993815810048",
        "-493399374030747471036018890494175/251658285736841065236836942273664",
        "418285003077108927126515545155/455369916679568501838710898688", "-15171723902781457/63532954684873728",
        "1501203688494867/9434957026426880",
        "34188549803371802849576690267872548602326398788953/42496542183406636759747616530102745233754251202880",
        "0", "-18971246281693750/1138830954584356089", "-59230464334542700/2765732318276293359",
        "5147939981309774383134903239728881770043/305929030949718561059100251282184099064",
        "-3625720213550267723370658302114678215563058405229078120/324512095420929759624784749347170583153994213035432256",
        "-60305503318319653518547439098565661266182518307816/17856872599361492097414471889911176856851308259643",
        "-1036461878759982363277481306266144563833492657780645/67994467493450618815596186448164392374006801924608",
        "128398681100219349205889126776607047000/7473801441221286756994805323613917077",
        "-49156374556350058671822606102117/9039888303968618912866414995904",
        "12253036339964386945/8828680926314891943", "-647188390508758231059/1092148506009694282240",
        "10915833599872/368729913707897",
        "-4939337286263213195547765488387521892799075623007291241961609516532/5408250052307451520718178852915698257207815452080611897685945761264",
        "0", "7588799849596321243074032368290625/3147217749590114939838670370597819616",
        "16870665568420512953501332587233725/955405388268427749593882076788623812",
        "-808642515918378014850308582271476014669568437579087796060/54447992506702009927986632715967769032585338753056786562",
        "4610328329649866588704236006423149172472141907645890762410296050212/2135428689710103309390449198881479603148467934048051598947383737508",
        "4159963831215576225909381034291748993887819834160487158570788681/1040533184037697645660563795162185415624171583014576682740416336",
        "7381392142124351279433801934148706553542137071890521365664606664449580/259596002510757672994472584939953516345975141699869371088925396540699",
        "-3336834334584052813468828675971359774694437229547862706920/132102862435303266640535426836147775872819092781208127980",
        "426619379967412086875039012957475466130081426048213491790/55162410119399855550108207148248549410926885937244965785",
        "-630755628691078947314733435975762542732598947/333503232300511886435069380727586592765317456",
        "1522350657470125698997653827133798314909646891/1520094067152619944607524353149267399623188480",
        "305575414262755427083262606101825880/65839748482572312891297405431209259829",
        "256624643108055110568255672032710477795/22874609758516552135947898572671559986304",
        "-571597862947184314270186718640978947715678864684269066846/2077055064880303907616135969012720011907767004397744786340",
        "0", "66981514290625/1829501741761029", "43495576635800/4443075658562499",
        "-127865248353371207265315478623656127/10401415428935853634424440540325344",
        "1316565142658075739557231574080234814338066993483960326560/92668695535091962564795912774190176478892159517481612467",
        "3881494143728609118531066904799685950051960514138645179820/2446349095978358868919950548516272963929118212742344026549",
        "162922667049680755852592453758428194006198229544701786842910/66288722243155885736983218667976563740242178853010092663614",
        "-43986024977384568043684084266385512680544563954/4922783599524658241955780540171948284522386185",
        "285912200202585226675651763671663063668290787/65371192072964016939690070594254881767827200",
        "-6776815256667778089672518929/3693654613173093729492918708",
        "398946554885847045598775476868169/344154261237450078839899047372800",
        "-76630698033396272/4432017119727044925", "28401702316003037/1469612686944417840",
        "66049942462586341419969330578128801/12691068622536592094919763114637498325",
        "83940754497395557520874219603241359529066454343054832302344735/64192596456995578553872477759926464976144474354415663868673233",
        "0", "892543892035485503125/51401651664490002607536", "-12732238157949399705325/686579204375687891972088",
        "5290376174838819557032232941734928484252549/357179779572898187570048915214361602000384",
        "26873229338017506937199991804717456666650215387938173031932210/2863980005760296740624015421425947092438943496681472214589916",
        "-1976497866818803305857417297961598735637414137241493515492778650/378029217824623393200881653405474359138017953416246216408422692",
        "-1002860756304839757040188283199900676042073362417943601440986856950/20486915674765670626893195919603679319429068544972409068469849579",
        "87398661196965758104117684348440686081062878816711392590/2282122412587168891929052689609009868137678763277087160",
        "-7922242431969626895355493632206885458496418610471389/748272134517487495468365669337985635214015258726400",
        "2777643183645212014464950387658055285/1141545470045611737197667093465955392",
        "-1372659703515496442825084239977218110461/1313121960368535725613950174847107891200",
        "6144417902699179309851023/85608793932459282773805825",
        "140294243355138853053241/64884622846351585391642880",
        "168671028523891369934964082754523881107337/24062875279623260368388427013982199424119600", "0"
    };
    static constexpr std::array<const char*, 17> b = {
        "63818747/5262156900", "0", "0", "0", "0", "0", "22555300000000/261366897038247",
        "1696514453125/6717619827072", "-45359872/229764843", "19174962087/94371046000", "-19310468/929468925",
        "16089185487681/146694672924800", "1592709632/41841694125", "52675701958271/4527711056573100",
        "12540904472870916741199505796420811396/2692319557780977037279406889319526430375", "0", "0"
    };
    static constexpr std::array<const char*, 17> b_hat = {
        "27121957/1594593000", "0", "0", "0", "0", "0", "4006163300000/55441463008113", "9466403125/25445529648",
        "-163199648/406149975", "23359833/69636250", "-18491714/140828625", "11052304606701/58344472186000",
        "1191129152/44377554375", "2033811086741/124730332137000",
        "3616943474975740389660406409450169802/951830146690244407118982233597812374375", "0", "0"
    };
    static constexpr std::array<const char*, 17> bp = {
        "63818747/5262156900", "0", "0", "0", "0", "0", "451106000000000/4965971043726693",
        "8482572265625/26870479308288", "-181439488/689294529", "57524886261/188742092000", "-38620936/929468925",
        "144802669389129/586778691699200", "6370838528/41841694125", "368729913707897/4527711056573100",
        "111940113324845802831946788738852162520696/1316544263754897771229629968877248424453375",
        "-113178587/12362232960", "1/40"
    };
    static constexpr std::array<const char*, 17> bp_hat = {
        "27121957/1594593000", "0", "0", "0", "0", "0", "4217014000000/55441463008113", "47332015625/101782118592",
        "-652798592/1218449925", "70079499/139272500", "-36983428/140828625", "99470741460309/233377888744000",
        "4764516608/44377554375", "14236677607187/124730332137000",
        "198066487470143918516004831967805004004/2855490440070733221356946700793437123125", "1/50", "0"
    };
};

// A table of an embedded RKN pair: nodes, the strictly lower triangle of a
// (row by row), the weights of q and p and their embedded counterparts.
template <class P>
concept rkn_pair_table = requires {
    { P::name } -> std::convertible_to<const char*>;
    { P::stages } -> std::convertible_to<int>;
    { P::order } -> std::convertible_to<int>;
    { P::embedded_order } -> std::convertible_to<int>;
    requires P::c.size() == std::size_t(P::stages);
    requires P::a.size() == std::size_t(P::stages * (P::stages - 1) / 2);
    requires P::b.size() == std::size_t(P::stages) && P::b_hat.size() == std::size_t(P::stages);
    requires P::bp.size() == std::size_t(P::stages) && P::bp_hat.size() == std::size_t(P::stages);
};

// A pair with a continuous extension (dense output): b_dense, bp_dense.
template <class P>
concept rkn_dense_table = rkn_pair_table<P> && requires {
    requires P::b_dense.size() == std::size_t(P::stages);
    requires P::bp_dense.size() == std::size_t(P::stages);
};

namespace detail {
// A decimal number as text in scalar S: by S's own parser when it has one
// (Boost.Multiprecision), otherwise by from_chars (locale-independent).
template <class S>
S decimal_as(const char* first, const char* last) {
    if constexpr (std::is_constructible_v<S, const char*> && !std::is_arithmetic_v<S>) {
        return S(std::string(first, last).c_str());
    } else {
        long double v = 0;
        const auto r = std::from_chars(first, last, v);
        if (r.ec != std::errc() || r.ptr != last)
            throw invalid_argument("rkn pair: coefficient '" + std::string(first, last) + "'; expected a decimal number");
        return S(v);
    }
}
// "p/q" or a decimal: a published coefficient in scalar S (within 1.5 ulp).
template <class S>
S coefficient_as(const char* text) {
    const char* end = text + std::strlen(text);
    const char* slash = std::find(text, end, '/');
    if (slash == end) return decimal_as<S>(text, end);
    return decimal_as<S>(text, slash) / decimal_as<S>(slash + 1, end);
}
}  // namespace detail

// The coefficients of pair P in scalar S, a as a full (lower-triangular) matrix.
template <class P, class S>
    requires rkn_pair_table<P>
struct rkn_coefficients {
    static constexpr int s = P::stages;
    std::array<S, s> c{}, b{}, b_hat{}, bp{}, bp_hat{};
    std::array<std::array<S, s>, s> a{};
    bool fsal = false;  // c_s = 1, a_sj = b_j, b_s = 0: stage s's force is F(q_new)

    rkn_coefficients() {
        std::size_t k = 0;
        for (int i = 0; i < s; ++i) {
            c[i] = detail::coefficient_as<S>(P::c[i]);
            b[i] = detail::coefficient_as<S>(P::b[i]);
            b_hat[i] = detail::coefficient_as<S>(P::b_hat[i]);
            bp[i] = detail::coefficient_as<S>(P::bp[i]);
            bp_hat[i] = detail::coefficient_as<S>(P::bp_hat[i]);
            for (int j = 0; j < i; ++j) a[i][j] = detail::coefficient_as<S>(P::a[k++]);
        }
        fsal = c[s - 1] == S(1) && b[s - 1] == S(0);
        for (int j = 0; j < s - 1; ++j) fsal = fsal && a[s - 1][j] == b[j];
    }
};

// Tolerances and limits of the step-size control.
struct rkn_control {
    double absolute_tolerance = 1e-10;  // per component of q and p
    double relative_tolerance = 1e-10;  // of max(|y_old|, |y_new|)
    double dt_initial = 0;              // first trial step; 0 means (t_end - t0) / 100
    double dt_min = 0;                  // 0 means 1e-12 (t_end - t0)
    double dt_max = std::numeric_limits<double>::infinity();
    double max_factor = 5;    // largest growth of the step from one step to the next
    double min_factor = 0.2;  // largest shrink
    double safety = 0.9;
};

struct rkn_summary {
    std::size_t accepted = 0;
    std::size_t rejected = 0;
    double t = 0;
    double dt_smallest = std::numeric_limits<double>::infinity();  // of the accepted steps
    double dt_largest = 0;
    double largest_error = 0;  // of the accepted steps, in units of the tolerance (<= 1)
    std::uint64_t force_evaluations = 0;
};

// Any pair P on a separable Hamiltonian with linear velocity(p).
template <class H, class State, rkn_pair_table P>
    requires phase_space_state<State> && separable_hamiltonian<H, typename State::vector>
class rkn_pair_stepper {
public:
    using state_type = State;
    using scalar = typename State::scalar;
    using vector = typename State::vector;
    using pair_type = P;
    static constexpr int stages = P::stages;

    explicit rkn_pair_stepper(H hamiltonian)
        : h_(std::move(hamiltonian)), who_(std::string("rkn_pair_stepper<") + P::name + ">") {}

    // One step of size dt (dt < 0 runs backwards), with no error control.
    void step(State& x, scalar dt) {
        check(x, dt, "step");
        advance_trial(x, dt, false);
        accept(x);
    }

    // The trial step from x by dt, x untouched: returns the error estimate
    // in units of the tolerance (the root-mean-square norm of Hairer, Norsett
    // & Wanner I, eq. II.4.11, over q and p). accept(x) then moves x to it.
    scalar attempt(const State& x, scalar dt, double absolute_tolerance, double relative_tolerance) {
        check(x, dt, "attempt");
        advance_trial(x, dt, true);
        using std::abs;
        using std::max;
        using std::sqrt;
        const Eigen::Index n = x.size();
        if (n == 0) return scalar(0);
        scalar sum(0);
        for (Eigen::Index i = 0; i < n; ++i) {
            const scalar sq = scalar(absolute_tolerance) + scalar(relative_tolerance) * max(abs(x.q[i]), abs(trial_.q[i]));
            const scalar sp = scalar(absolute_tolerance) + scalar(relative_tolerance) * max(abs(x.p[i]), abs(trial_.p[i]));
            sum += (error_q_[i] / sq) * (error_q_[i] / sq) + (error_p_[i] / sp) * (error_p_[i] / sp);
        }
        return sqrt(sum / scalar(2 * n));
    }
    void accept(State& x) {
        if (!trial_ready_)
            throw invalid_argument(std::string("rkn_pair_stepper<") + P::name +
                                   ">::accept: no trial step to accept; expected attempt() before");
        std::swap(x, trial_);  // trial_ now holds the state before the step (for dense output)
        trial_ready_ = false;
        dense_valid_ = true;
    }

    // Dense output inside the last accepted step, at t + theta dt with 0 <= theta <= 1.
    State dense_output(scalar theta) const
        requires rkn_dense_table<P>
    {
        if (!dense_valid_)
            throw invalid_argument("rkn_pair_stepper::dense_output: no accepted step yet; expected a step before");
        using std::isfinite;
        if (!isfinite(theta) || theta < scalar(0) || theta > scalar(1))
            throw invalid_argument("rkn_pair_stepper::dense_output: theta = " + detail::number(theta) +
                                   "; expected 0 <= theta <= 1");
        State y = trial_;
        const scalar th = theta * dt_;
        vector uq = vector::Zero(y.size()), kp = vector::Zero(y.size());
        for (int i = 0; i < stages; ++i) {
            scalar wq(0), wp(0), power(1);
            for (int k = 0; k < 5; ++k, power *= theta) {
                wq += dense_.b[i][k] * power;
                wp += dense_.bp[i][k] * power;
            }
            uq += wq * u_[i];
            kp += wp * k_[i];
        }
        y.q = trial_.q + th * v0_ + (th * th) * uq;
        y.p = trial_.p + th * kp;
        return y;
    }

    std::uint64_t force_evaluations() const { return force_evaluations_; }
    std::uint64_t velocity_evaluations() const { return velocity_evaluations_; }
    void reset_counters() { force_evaluations_ = velocity_evaluations_ = 0; }
    bool first_same_as_last() const { return co_.fsal; }
    const H& hamiltonian() const { return h_; }

    void check(const State& x, scalar dt, const char* who) const {
        using std::isfinite;
        if (!isfinite(dt) || dt == scalar(0))
            throw invalid_argument(who_ + "::" + who + ": dt = " + detail::number(dt) +
                                   "; expected a finite non-zero step size");
        check_state(h_, x, who_.c_str());  // no string built per step
    }

private:
    void size_workspace(Eigen::Index n) {
        if (v0_.size() == n) return;
        v0_.resize(n), Q_.resize(n), error_q_.resize(n), error_p_.resize(n), sum_.resize(n);
        for (int i = 0; i < stages; ++i) k_[i].resize(n), u_[i].resize(n);
        trial_ = State(n);
        known_[0].valid = known_[1].valid = false;
    }

    void force_at(const vector& q, int i) {
        force(h_, q, k_[i]);
        velocity(h_, k_[i], u_[i]);
        ++force_evaluations_;
        ++velocity_evaluations_;
    }

    // M^-1 linear: probed once with p and the first force.
    void check_linear_velocity(const State& x) {
        using std::abs;
        const Eigen::Index n = x.size();
        vector v_sum(n), v_twice(n);
        velocity(h_, vector(x.p + k_[0]), v_sum);
        velocity(h_, vector(scalar(2) * x.p), v_twice);
        velocity_evaluations_ += 2;
        scalar worst(0), size(0);
        for (Eigen::Index i = 0; i < n; ++i) {
            const scalar d1 = abs(v_sum[i] - v0_[i] - u_[0][i]), d2 = abs(v_twice[i] - scalar(2) * v0_[i]);
            worst = d1 > worst ? d1 : worst;
            worst = d2 > worst ? d2 : worst;
            const scalar s = abs(v0_[i]) + abs(u_[0][i]);
            size = s > size ? s : size;
        }
        if (worst > scalar(1024) * std::numeric_limits<scalar>::epsilon() * size)
            throw invalid_argument(std::string("rkn_pair_stepper<") + P::name +
                                   ">: velocity(p) is not linear in p (velocity(p + F) - velocity(p) - velocity(F) "
                                   "or velocity(2p) - 2 velocity(p) is " + detail::number(worst) +
                                   "); expected a quadratic kinetic energy T = p M^-1 p / 2, as Runge-Kutta-Nystrom "
                                   "methods need (use a splitting method for other kinetic energies)");
        linear_checked_ = true;
    }

    void advance_trial(const State& x, scalar dt, bool estimate) {
        const Eigen::Index n = x.size();
        size_workspace(n);
        velocity(h_, x.p, v0_);
        ++velocity_evaluations_;
        if (known_[0].holds(x.q)) {
            k_[0] = known_[0].k;
            u_[0] = known_[0].u;
        } else if (known_[1].holds(x.q)) {
            k_[0] = known_[1].k;
            u_[0] = known_[1].u;
        } else {
            force_at(x.q, 0);
        }
        if (!linear_checked_) check_linear_velocity(x);
        const scalar h2 = dt * dt;
        for (int i = 1; i < stages; ++i) {
            sum_.setZero();
            for (int j = 0; j < i; ++j)
                if (co_.a[i][j] != scalar(0)) sum_ += co_.a[i][j] * u_[j];
            Q_ = x.q + (co_.c[i] * dt) * v0_ + h2 * sum_;
            force_at(Q_, i);
        }
        // The start's force is kept for a retry of this step (after a rejection).
        known_[0].keep(x.q, k_[0], u_[0]);
        if (co_.fsal) {
            trial_.q = Q_;  // stage s is q_new itself
        } else {
            sum_.setZero();
            for (int i = 0; i < stages; ++i)
                if (co_.b[i] != scalar(0)) sum_ += co_.b[i] * u_[i];
            trial_.q = x.q + dt * v0_ + h2 * sum_;
        }
        sum_.setZero();
        for (int i = 0; i < stages; ++i)
            if (co_.bp[i] != scalar(0)) sum_ += co_.bp[i] * k_[i];
        trial_.p = x.p + dt * sum_;
        if (estimate) {
            error_q_.setZero();
            error_p_.setZero();
            for (int i = 0; i < stages; ++i) {
                error_q_ += (co_.b[i] - co_.b_hat[i]) * u_[i];
                error_p_ += (co_.bp[i] - co_.bp_hat[i]) * k_[i];
            }
            error_q_ *= h2;
            error_p_ *= dt;
        }
        if (co_.fsal)  // the next step starts from q_new, whose force is stage s's
            known_[1].keep(trial_.q, k_[stages - 1], u_[stages - 1]);
        else
            known_[1].valid = false;
        dt_ = dt;
        dense_valid_ = false;
        trial_ready_ = true;
    }

    struct dense_weights {
        std::array<std::array<scalar, 5>, stages> b{}, bp{};
    };
    static dense_weights make_dense() {
        dense_weights d;
        if constexpr (rkn_dense_table<P>)
            for (int i = 0; i < stages; ++i)
                for (int k = 0; k < 5; ++k) {
                    d.b[i][k] = detail::coefficient_as<scalar>(P::b_dense[i][k]);
                    d.bp[i][k] = detail::coefficient_as<scalar>(P::bp_dense[i][k]);
                }
        return d;
    }

    H h_;
    std::string who_;
    rkn_coefficients<P, scalar> co_;
    dense_weights dense_ = make_dense();
    std::array<vector, stages> k_, u_;  // forces and accelerations of the stages
    // A force already evaluated, with the q it belongs to: the start of the
    // last attempt, and (FSAL) its end.
    struct known_force {
        vector q, k, u;
        bool valid = false;
        bool holds(const vector& x) const { return valid && q.size() == x.size() && q == x; }
        void keep(const vector& x, const vector& k_, const vector& u_) {
            q = x, k = k_, u = u_;
            valid = true;
        }
    };
    std::array<known_force, 2> known_;
    vector v0_, Q_, sum_, error_q_, error_p_;
    State trial_;
    scalar dt_{};
    bool linear_checked_ = false, dense_valid_ = false, trial_ready_ = false;
    std::uint64_t force_evaluations_ = 0, velocity_evaluations_ = 0;
};

template <rkn_pair_table P, class State, class H>
rkn_pair_stepper<H, State, P> make_rkn_stepper(H hamiltonian) {
    return rkn_pair_stepper<H, State, P>(std::move(hamiltonian));
}

// From t0 to exactly t_end with the step size controlled: a step is accepted
// when its error estimate, in units of the tolerance, is at most 1; the next
// step is h * safety * err^-alpha * err_prev^beta (the PI controller of
// Gustafsson 1991, ACM TOMS 17, 533-554; Hairer, Norsett & Wanner I, sect.
// II.4, "stabilized step size control"), alpha = 0.7/k, beta = 0.4/k with
// k = embedded order + 1, limited to [min_factor, max_factor]; after a
// rejection the step only shrinks, by err^(-1/k). A rejected step that cannot
// shrink below dt_min stops the run with an integration_error naming the time
// and step size; x is left at the last accepted step. observer(x, t) is
// called at t0 and after every accepted step.
template <class H, class State, class P, class Observer = no_observer>
rkn_summary integrate_controlled(rkn_pair_stepper<H, State, P>& stepper, State& x, typename State::scalar t0,
                                 typename State::scalar t_end, rkn_control control = {}, Observer&& observer = {}) {
    using T = typename State::scalar;
    using detail::number;
    using std::isfinite;
    const char* who = "integrate_controlled";
    if (!isfinite(t0) || !isfinite(t_end) || !(t_end > t0))
        throw invalid_argument(std::string(who) + ": t_end = " + number(t_end) + " with t0 = " + number(t0) +
                               "; expected finite times with t_end > t0");
    const auto positive = [&](double v, const char* what) {
        if (!(v > 0) || !std::isfinite(v))
            throw invalid_argument(std::string(who) + ": " + what + " = " + number(v) + "; expected a finite value > 0");
    };
    positive(control.absolute_tolerance, "absolute_tolerance");
    positive(control.relative_tolerance, "relative_tolerance");
    positive(control.safety, "safety");
    if (!(control.max_factor > 1) || !std::isfinite(control.max_factor) || !(control.min_factor > 0) ||
        !(control.min_factor < 1))
        throw invalid_argument(std::string(who) + ": max_factor = " + number(control.max_factor) +
                               ", min_factor = " + number(control.min_factor) +
                               "; expected a finite max_factor > 1 and 0 < min_factor < 1");
    const double span = static_cast<double>(t_end - t0);
    if (control.dt_initial == 0) control.dt_initial = span / 100;
    if (control.dt_min == 0) control.dt_min = 1e-12 * span;
    if (!(control.dt_min > 0) || !(control.dt_max >= control.dt_min) || !(control.dt_initial > 0) ||
        !std::isfinite(control.dt_initial))
        throw invalid_argument(std::string(who) + ": dt_min = " + number(control.dt_min) + ", dt_initial = " +
                               number(control.dt_initial) + ", dt_max = " + number(control.dt_max) +
                               "; expected 0 < dt_min <= dt_max and a finite dt_initial > 0");
    stepper.check(x, T(control.dt_initial), who);

    const double k = P::embedded_order + 1;
    const double alpha = 0.7 / k, beta = 0.4 / k;
    rkn_summary r;
    const auto f0 = stepper.force_evaluations();
    constexpr bool observed = !std::is_same_v<std::decay_t<Observer>, no_observer>;
    if constexpr (observed) observer(std::as_const(x), t0);
    T t = t0;
    double dt = std::clamp(control.dt_initial, control.dt_min, control.dt_max);
    double previous_error = 1;
    bool after_rejection = false;
    while (t < t_end) {
        const bool last = T(dt) >= t_end - t;
        const T h = last ? t_end - t : T(dt);
        const double hd = static_cast<double>(h);
        double err = static_cast<double>(stepper.attempt(x, h, control.absolute_tolerance, control.relative_tolerance));
        if (!std::isfinite(err)) err = HUGE_VAL;
        if (err <= 1) {
            stepper.accept(x);
            t = last ? t_end : t + h;
            ++r.accepted;
            r.dt_smallest = std::min(r.dt_smallest, hd);
            r.dt_largest = std::max(r.dt_largest, hd);
            r.largest_error = std::max(r.largest_error, err);
            if constexpr (observed) observer(std::as_const(x), t);
            const double e = std::max(err, 1e-10);
            double factor = control.safety * std::pow(e, -alpha) * std::pow(previous_error, beta);
            factor = std::clamp(factor, control.min_factor, after_rejection ? 1.0 : control.max_factor);
            previous_error = e;
            after_rejection = false;
            if (!last) dt = std::clamp(hd * factor, control.dt_min, control.dt_max);
        } else {
            ++r.rejected;
            after_rejection = true;
            if (hd <= control.dt_min * (1 + 1e-12) && !last)
                throw integration_error(std::string(who) + ": step size underflow at t = " + number(t) + ": dt = " +
                                            number(hd) + " is dt_min and its error estimate is " + number(err) +
                                            " times the tolerance; expected a larger tolerance or a smaller dt_min; "
                                            "the state is left at t",
                                        r.accepted + 1, static_cast<double>(t));
            const double factor = std::isfinite(err) ? control.safety * std::pow(err, -1.0 / k) : control.min_factor;
            dt = std::max(hd * std::clamp(factor, control.min_factor, 1.0), control.dt_min);
        }
    }
    r.t = static_cast<double>(t_end);
    r.force_evaluations = stepper.force_evaluations() - f0;
    return r;
}

}  // namespace sympl
