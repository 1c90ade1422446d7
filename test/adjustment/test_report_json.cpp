// report_json.h: the -json document of an AdjustmentReport, checked field by field against the
// report it was written from (a user of the C++ API gets what pcl_ls3d_register writes).
#include <pcl_ls3d/adjustment/parameter_block.h>
#include <pcl_ls3d/adjustment/report_json.h>

#include <nlohmann/json.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pcl_ls3d;

namespace {

AdjustmentReport
someReport()
{
  AdjustmentReport r;
  r.termination = TerminationType::CONVERGED;
  r.message = "changes below the epsilons";
  r.iterations = 7;
  r.sigma0 = 0.0123;
  for (int i = 0; i < 7; ++i) {
    r.parameters[i] = 0.1 * (i + 1);
    r.sigmas[i] = 0.01 * (i + 1);
    r.sigmas_formal[i] = 0.001 * (i + 1);
    r.determinable[static_cast<std::size_t>(i)] = i != 6;
    r.fixed[static_cast<std::size_t>(i)] = i == 6;
  }
  r.sigmas[SCALE] = std::numeric_limits<double>::infinity();  // undeterminable: no number in JSON
  r.qxx = Matrix7d::Identity() * 2.0;
  r.correlation(0, 1) = r.correlation(1, 0) = -0.25;
  r.local_origin_target = Eigen::Vector3d(1.0, 2.0, 3.0);
  r.local_origin_source = Eigen::Vector3d(-1.0, 0.5, 0.0);
  IterationRecord it;
  it.iteration = 1;
  it.sigma0 = 0.5;
  it.observations_used = 900;
  it.extrapolated = true;
  r.log.push_back(it);
  r.observations_used = 900;
  r.redundancy = 894;
  return r;
}

TEST(ReportJson, EveryFieldComesFromTheReport)
{
  const AdjustmentReport r = someReport();
  ReportFrame frame;
  frame.transformation(0, 3) = 12.5;
  frame.origin = Eigen::Vector3d(500000.0, 5000000.0, 100.0);
  frame.cloud_origin = Eigen::Vector3d(7.0, 8.0, 9.0);
  const nlohmann::json j = nlohmann::json::parse(adjustmentReportJson(r, true, frame));

  EXPECT_TRUE(j.at("converged").get<bool>());
  EXPECT_EQ(j.at("termination"), terminationTypeToString(r.termination));
  EXPECT_EQ(j.at("message"), r.message);
  EXPECT_EQ(j.at("iterations"), 7);
  EXPECT_DOUBLE_EQ(j.at("sigma0").get<double>(), r.sigma0);
  EXPECT_DOUBLE_EQ(j.at("transformation")[0][3].get<double>(), 12.5);
  EXPECT_DOUBLE_EQ(j.at("transformation")[3][3].get<double>(), 1.0);
  const auto& names = similarityParameterNames();
  for (std::size_t i = 0; i < 7; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    EXPECT_DOUBLE_EQ(j.at("parameters").at(names[i]).get<double>(), r.parameters[k]) << names[i];
    EXPECT_DOUBLE_EQ(j.at("sigmas_formal").at(names[i]).get<double>(), r.sigmas_formal[k]) << names[i];
    EXPECT_EQ(j.at("determinable").at(names[i]).get<bool>(), r.determinable[i]) << names[i];
    EXPECT_EQ(j.at("fixed").at(names[i]).get<bool>(), r.fixed[i]) << names[i];
  }
  EXPECT_TRUE(j.at("sigmas").at(names[SCALE]).is_null());  // JSON has no infinity
  EXPECT_DOUBLE_EQ(j.at("sigmas").at(names[0]).get<double>(), r.sigmas[0]);
  EXPECT_DOUBLE_EQ(j.at("qxx")[2][2].get<double>(), 2.0);
  EXPECT_DOUBLE_EQ(j.at("correlation")[0][1].get<double>(), -0.25);
  ASSERT_EQ(j.at("log").size(), 1u);
  EXPECT_EQ(j.at("log")[0].at("observations_used"), 900);
  EXPECT_TRUE(j.at("log")[0].at("extrapolated").get<bool>());
  EXPECT_EQ(j.at("redundancy"), 894);
  // Local origins are reported in the files' coordinates: the report's plus the frame's origin.
  EXPECT_DOUBLE_EQ(j.at("local_origin")[0].get<double>(), 500001.0);
  EXPECT_DOUBLE_EQ(j.at("local_origin_source")[1].get<double>(), 5000000.5);
  EXPECT_DOUBLE_EQ(j.at("cloud_origin")[2].get<double>(), 9.0);
  EXPECT_FALSE(adjustmentReportJson(r, true, frame, 2).find('\n') == std::string::npos);  // indented
}

TEST(ReportJson, ParameterModelTextsRoundTrip)
{
  for (const ParameterModel m : {ParameterModel::SIMILARITY_7, ParameterModel::RIGID_6,
                                 ParameterModel::TRANSLATION_3, ParameterModel::HEIGHT_1}) {
    ParameterModel back = ParameterModel::RIGID_6;
    ASSERT_TRUE(parseParameterModel(parameterModelName(m), back));
    EXPECT_EQ(back, m);
  }
  ParameterModel m = ParameterModel::RIGID_6;
  EXPECT_TRUE(parseParameterModel("1", m));
  EXPECT_EQ(m, ParameterModel::HEIGHT_1);
  EXPECT_FALSE(parseParameterModel("5", m));
  EXPECT_FALSE(parseParameterModel("6x", m));
  EXPECT_EQ(m, ParameterModel::HEIGHT_1);  // untouched
}

}  // namespace
